#include "SegmentPanel.h"

#include "MainActions.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QToolButton>
#include <QVBoxLayout>

SegmentPanel::SegmentPanel(MainActions* actions, QWidget* parent)
  : QWidget(parent)
{
  auto* layout = new QVBoxLayout(this);
  auto* form = new QFormLayout;
  layout->addLayout(form);
  this->Method = new QComboBox(this);
  this->Method->setObjectName("segmentationMethod");
  this->Method->addItems({ "Threshold", "Vesselness" });
  form->addRow("Method", this->Method);
  this->Threshold = new QDoubleSpinBox(this);
  this->Threshold->setObjectName("lumenThreshold");
  this->Threshold->setRange(-1e6, 1e6);
  this->Threshold->setValue(250.0);
  form->addRow("Lumen above", this->Threshold);
  this->Smoothing = new QDoubleSpinBox(this);
  this->Smoothing->setObjectName("smoothing");
  this->Smoothing->setRange(0.0, 1.0);
  this->Smoothing->setSingleStep(0.1);
  this->Smoothing->setValue(0.5);
  form->addRow("Smoothing", this->Smoothing);
  layout->addWidget(ActionButton(actions->Segment, this, "segmentButton"));
  layout->addStretch(1);
}

bender::SegmentationSettings SegmentPanel::settings() const
{
  bender::SegmentationSettings settings;
  settings.segmentation.method = this->Method->currentIndex() == 1
    ? bender::SegmentationMethod::Vesselness
    : bender::SegmentationMethod::Threshold;
  settings.segmentation.lower = this->Threshold->value();
  settings.surface.smoothing = this->Smoothing->value();
  return settings;
}
