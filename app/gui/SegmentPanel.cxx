#include "SegmentPanel.h"

#include "HistogramWidget.h"
#include "MainActions.h"
#include "SegmentVolume.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QLocale>
#include <QToolButton>
#include <QVBoxLayout>

#include <cmath>

SegmentPanel::SegmentPanel(MainActions* actions, QWidget* parent)
  : QWidget(parent)
{
  auto* layout = new QVBoxLayout(this);
  auto* form = new QFormLayout;
  layout->addLayout(form);
  this->Method = new QComboBox(this);
  this->Method->setObjectName("segmentationMethod");
  this->Method->addItems({ "Threshold", "Vesselness" });
  this->Method->setToolTip("Threshold: the lumen is the connected bright region above the "
                           "threshold. Vesselness: tubular bright structures (Frangi filter)");
  form->addRow("Method", this->Method);
  this->Threshold = new QDoubleSpinBox(this);
  this->Threshold->setObjectName("lumenThreshold");
  this->Threshold->setRange(-1e6, 1e6);
  this->Threshold->setValue(250.0);
  this->Threshold->setToolTip("Voxels at or above this intensity are lumen (see the histogram "
                              "below: the red part is kept)");
  form->addRow("Lumen above", this->Threshold);
  this->Histogram = new HistogramWidget(this);
  form->addRow(this->Histogram);
  this->Kept = new QLabel(this);
  this->Kept->setObjectName("thresholdKeeps");
  this->Kept->setWordWrap(true);
  form->addRow(this->Kept);
  this->Smoothing = new QDoubleSpinBox(this);
  this->Smoothing->setObjectName("smoothing");
  this->Smoothing->setRange(0.0, 1.0);
  this->Smoothing->setSingleStep(0.1);
  this->Smoothing->setValue(0.5);
  this->Smoothing->setToolTip("Smoothing of the extracted surface, 0 (none) to 1 (strong)");
  form->addRow("Smoothing", this->Smoothing);
  layout->addWidget(ActionButton(actions->Segment, this, "segmentButton"));
  this->Warning = new QLabel(this);
  this->Warning->setObjectName("segmentationWarning");
  this->Warning->setWordWrap(true);
  this->Warning->setStyleSheet("color: #d90;");
  this->Warning->hide();
  layout->addWidget(this->Warning);
  layout->addStretch(1);

  connect(this->Threshold,
    QOverload<double>::of(&QDoubleSpinBox::valueChanged),
    this,
    [this](double value)
    {
      this->Histogram->setThreshold(value);
      this->showKept();
    });
  connect(this->Histogram,
    &HistogramWidget::thresholdPicked,
    this,
    [this](double value)
    {
      // Whole numbers on integer volumes.
      this->Threshold->setValue(this->EightBit ? std::round(value) : value);
    });
  this->Histogram->setThreshold(this->Threshold->value());
  this->showKept();
  // The panel's own defaults (250, 0.5) are the base until a session's are set.
  this->Base.segmentation.lower = this->Threshold->value();
  this->Base.surface.smoothing = this->Smoothing->value();
  this->ShownThreshold = this->Threshold->value();
  this->ShownSmoothing = this->Smoothing->value();
}

bender::SegmentationSettings SegmentPanel::settings() const
{
  bender::SegmentationSettings settings = this->Base;
  settings.segmentation.method = this->Method->currentIndex() == 1
    ? bender::SegmentationMethod::Vesselness
    : bender::SegmentationMethod::Threshold;
  // The boxes show two decimals: a recovered 187.125 stays 187.125 until the user changes it.
  if (this->Threshold->value() != this->ShownThreshold)
  {
    settings.segmentation.lower = this->Threshold->value();
  }
  if (this->Smoothing->value() != this->ShownSmoothing)
  {
    settings.surface.smoothing = this->Smoothing->value();
  }
  return settings;
}

void SegmentPanel::setSettings(const bender::SegmentationSettings& settings)
{
  this->Base = settings;
  this->Method->setCurrentIndex(
    settings.segmentation.method == bender::SegmentationMethod::Vesselness ? 1 : 0);
  this->Threshold->setValue(settings.segmentation.lower);
  this->Smoothing->setValue(settings.surface.smoothing);
  this->ShownThreshold = this->Threshold->value();
  this->ShownSmoothing = this->Smoothing->value();
}

void SegmentPanel::showVolume(const std::shared_ptr<const bender::Volume>& volume)
{
  if (volume == this->Volume)
  {
    return;
  }
  this->Volume = volume;
  this->EightBit = false;
  if (!volume)
  {
    this->Histogram->setValues({});
    this->showKept();
    return;
  }
  this->Histogram->setValues(volume->voxels);
  this->EightBit = bender::IsEightBit(*volume);
  this->Histogram->setThreshold(this->Threshold->value());
  this->Warning->hide();
  this->showKept();
}

void SegmentPanel::showKept()
{
  if (this->Histogram->total() == 0)
  {
    this->Kept->setText("Load a volume to see its intensities.");
    return;
  }
  const std::size_t kept = this->Histogram->countAtOrAbove(this->Threshold->value());
  const double percent = 100.0 * static_cast<double>(kept) / this->Histogram->total();
  this->Kept->setText(QString("Intensities %1 to %2%3; the threshold keeps %4 voxels (%5%)")
                        .arg(this->Histogram->minimum(), 0, 'g', 5)
                        .arg(this->Histogram->maximum(), 0, 'g', 5)
                        .arg(this->EightBit ? " (8-bit)" : "")
                        .arg(QLocale::c().toString(static_cast<qulonglong>(kept)))
                        .arg(percent, 0, 'g', 3));
}

void SegmentPanel::showWarning(const std::string& warning)
{
  this->Warning->setText(QString::fromStdString(warning));
  this->Warning->setVisible(!warning.empty());
}
