#include "ExportPanel.h"

#include "MainActions.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHeaderView>
#include <QLabel>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QTableWidget>
#include <QToolButton>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

ExportOptionsForm::ExportOptionsForm(QWidget* parent)
  : QWidget(parent)
{
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  auto* form = new QFormLayout;
  layout->addLayout(form);
  this->Presets = new QComboBox(this);
  this->Presets->setObjectName("presetCombo");
  this->Presets->addItems({ "Custom", "OpenFOAM (m, named solids)", "TetGen (.smesh, m)" });
  this->Presets->setToolTip("OpenFOAM: capped, one ASCII STL with a solid per patch (wall, "
                            "inlet, outlet_1, ...) in metres, with the patches sidecar");
  form->addRow("Preset", this->Presets);
  this->Formats = new QComboBox(this);
  this->Formats->setObjectName("formatCombo");
  for (const bender::MeshFormat& format : bender::MeshFormats())
  {
    if (!format.CanWrite())
    {
      continue;
    }
    const QString label = QString::fromStdString(format.label);
    const QString name = QString::fromStdString(format.name);
    for (const bool ascii :
      format.encodingChoice ? std::vector<bool>{ false, true } : std::vector<bool>{ false })
    {
      const QString text =
        format.encodingChoice ? label + (ascii ? " (ASCII)" : " (binary)") : label;
      this->Formats->addItem(text, ascii ? name + ":ascii" : name);
    }
  }
  form->addRow("Format", this->Formats);
  this->Cap = new QCheckBox("Cap the open vessel ends (inlets and outlets)", this);
  this->Cap->setObjectName("capCheck");
  form->addRow("Caps", this->Cap);
  this->Patches = new QComboBox(this);
  this->Patches->setObjectName("patchesCombo");
  this->Patches->addItems({ "One surface",
    "Named solids per patch (ASCII, snappyHexMesh)",
    "One STL file per patch (shared rims)" });
  form->addRow("STL patches", this->Patches);
  this->Frame = new QComboBox(this);
  this->Frame->setObjectName("frameCombo");
  this->Frame->addItems({ "LPS (DICOM, ITK)", "RAS (Slicer, NIfTI)" });
  form->addRow("Frame", this->Frame);
  this->Unit = new QComboBox(this);
  this->Unit->setObjectName("unitCombo");
  this->Unit->addItems({ "millimetres (mm)", "metres (m, OpenFOAM)" });
  this->Unit->setToolTip("The surface is in millimetres; metres divide every coordinate by "
                         "1000. The frame and unit are stated in the file where it allows.");
  form->addRow("Unit", this->Unit);
  this->Sidecar = new QCheckBox("Write OUT.patches.json (centres, normals, areas, inside point)");
  this->Sidecar->setObjectName("sidecarCheck");
  form->addRow("Sidecar", this->Sidecar);
  this->Note = new QLabel(this);
  this->Note->setObjectName("exportNote");
  this->Note->setWordWrap(true);
  layout->addWidget(this->Note);

  connect(this->Presets,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    &ExportOptionsForm::applyPreset);
  connect(this->Formats,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    &ExportOptionsForm::formatChanged);
  connect(this->Patches,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    &ExportOptionsForm::patchesChanged);
  for (QComboBox* combo : { this->Frame, this->Unit })
  {
    connect(combo,
      QOverload<int>::of(&QComboBox::currentIndexChanged),
      this,
      &ExportOptionsForm::markCustom);
  }
  for (QCheckBox* check : { this->Cap, this->Sidecar })
  {
    connect(check, &QCheckBox::toggled, this, &ExportOptionsForm::markCustom);
  }
  this->formatChanged();
}

void ExportOptionsForm::markCustom()
{
  if (!this->Applying)
  {
    const QSignalBlocker block(this->Presets);
    this->Presets->setCurrentIndex(Custom);
  }
}

void ExportOptionsForm::applyPreset(int preset)
{
  if (preset == Custom)
  {
    return;
  }
  this->Applying = true;
  this->Cap->setChecked(true);
  this->Unit->setCurrentIndex(1);
  this->Frame->setCurrentIndex(0);
  this->Sidecar->setChecked(true);
  if (preset == OpenFoam)
  {
    this->Formats->setCurrentIndex(this->formatIndex("stl", true));
    this->Patches->setCurrentIndex(1);
  }
  else
  {
    this->Formats->setCurrentIndex(this->formatIndex("smesh"));
    this->Patches->setCurrentIndex(0);
  }
  this->Note->clear();
  this->Applying = false;
  const QSignalBlocker block(this->Presets);
  this->Presets->setCurrentIndex(preset);
}

void ExportOptionsForm::formatChanged()
{
  const bender::MeshFormat format = this->format();
  this->Patches->setEnabled(format.namedPatches);
  if (format.encodingChoice && !this->isAscii() && this->Patches->currentIndex() == 1)
  {
    // Named solids exist only in ASCII STL: say what changed instead of writing ASCII anyway.
    const QSignalBlocker block(this->Patches);
    this->Patches->setCurrentIndex(0);
    this->Note->setText("Named solids are ASCII STL only: STL patches set to \"One surface\".");
  }
  else
  {
    this->Note->clear();
  }
  this->markCustom();
}

void ExportOptionsForm::patchesChanged()
{
  const bender::MeshFormat format = this->format();
  if (this->Patches->currentIndex() == 1 && format.encodingChoice && !this->isAscii())
  {
    const QSignalBlocker block(this->Formats);
    this->Formats->setCurrentIndex(this->formatIndex(format.name, true));
    this->Note->setText("Named solids are ASCII STL only: the format is now \"STL (ASCII)\".");
  }
  else
  {
    this->Note->clear();
  }
  this->markCustom();
}

QString ExportOptionsForm::note() const
{
  return this->Note->text();
}

QString ExportOptionsForm::suffix() const
{
  const bender::MeshFormat format = this->format();
  return format.extensions.empty() ? QString() : QString::fromStdString(format.extensions.front());
}

int ExportOptionsForm::formatIndex(const std::string& name, bool ascii) const
{
  const QString entry = QString::fromStdString(name);
  return this->Formats->findData(ascii ? entry + ":ascii" : entry);
}

bender::MeshFormat ExportOptionsForm::format() const
{
  // The entry's data: the format's name, with ":ascii" for its ASCII entry.
  const QString name = this->Formats->currentData().toString().section(':', 0, 0);
  const auto format = bender::FindMeshFormatByName(name.toStdString());
  return format ? *format : bender::MeshFormat{};
}

bool ExportOptionsForm::isAscii() const
{
  return this->Formats->currentData().toString().endsWith(":ascii");
}

void ExportOptionsForm::copyFrom(const ExportOptionsForm& other)
{
  this->Applying = true;
  {
    const QSignalBlocker a(this->Formats), b(this->Patches);
    this->Formats->setCurrentIndex(other.Formats->currentIndex());
    this->Patches->setCurrentIndex(other.Patches->currentIndex());
  }
  this->Patches->setEnabled(other.Patches->isEnabled());
  this->Cap->setChecked(other.Cap->isChecked());
  this->Frame->setCurrentIndex(other.Frame->currentIndex());
  this->Unit->setCurrentIndex(other.Unit->currentIndex());
  this->Sidecar->setChecked(other.Sidecar->isChecked());
  this->Note->setText(other.Note->text());
  this->Applying = false;
  const QSignalBlocker c(this->Presets);
  this->Presets->setCurrentIndex(other.Presets->currentIndex());
}

bender::ExportSurfaceOptions ExportOptionsForm::options(const QString& path) const
{
  bender::ExportSurfaceOptions options;
  options.output = path.toStdString();
  // The file's format decides; the form's encoding and patches apply where that format has them.
  const auto written = bender::FindMeshFormat(path.toStdString());
  const bool chosen = written && written->name == this->format().name;
  options.stlEncoding = (chosen && written->encodingChoice && this->isAscii())
    ? bender::StlEncoding::Ascii
    : bender::StlEncoding::Binary;
  options.cap = this->Cap->isChecked();
  const int patches = written && written->namedPatches ? this->Patches->currentIndex() : 0;
  options.patches = patches == 1
    ? bender::StlPatchMode::Solids
    : (patches == 2 ? bender::StlPatchMode::Files : bender::StlPatchMode::Single);
  if (options.patches == bender::StlPatchMode::Solids)
  {
    options.stlEncoding = bender::StlEncoding::Ascii; // the form keeps the format in step
  }
  options.frame = this->Frame->currentIndex() == 1 ? bender::StlFrame::RAS : bender::StlFrame::LPS;
  options.unit = this->Unit->currentIndex() == 1 ? "m" : "mm";
  options.patchesJson = this->Sidecar->isChecked();
  return options;
}

ExportPanel::ExportPanel(MainActions* actions, QWidget* parent)
  : QWidget(parent)
{
  auto* layout = new QVBoxLayout(this);
  auto* prepare = new QGroupBox("Prepare for CFD", this);
  prepare->setObjectName("prepareGroup");
  auto* prepareLayout = new QVBoxLayout(prepare);
  auto* prepareForm = new QFormLayout;
  prepareLayout->addLayout(prepareForm);
  this->Clip = new QCheckBox("Clip the vessel ends perpendicular to the centerline", prepare);
  this->Clip->setObjectName("clipCheck");
  this->Clip->setChecked(true);
  this->Clip->setToolTip("Off: keep the open ends the surface has (an already open vessel)");
  prepareForm->addRow("Ends", this->Clip);
  this->InletFactor = new QDoubleSpinBox(prepare);
  this->InletFactor->setObjectName("inletFactor");
  this->OutletFactor = new QDoubleSpinBox(prepare);
  this->OutletFactor->setObjectName("outletFactor");
  for (QDoubleSpinBox* box : { this->InletFactor, this->OutletFactor })
  {
    box->setRange(0.0, 100.0);
    box->setDecimals(1);
    box->setSuffix(" x radius");
  }
  this->InletFactor->setValue(10.0);
  this->OutletFactor->setValue(5.0);
  prepareForm->addRow("Inlet extension", this->InletFactor);
  prepareForm->addRow("Outlet extensions", this->OutletFactor);
  this->Ends = new QTableWidget(0, 5, prepare);
  this->Ends->setObjectName("endsTable");
  this->Ends->setHorizontalHeaderLabels(
    { "Name", "Role", "Radius\n(mm)", "Extension\n(x r)", "Cut at\n(mm from end)" });
  this->Ends->horizontalHeaderItem(CutColumn)->setToolTip(
    "Where the end is cut: mm along the centerline from the vessel end (drag the "
    "end's disc in the 3D view, or type)");
  this->Ends->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  this->Ends->horizontalHeader()->setSectionResizeMode(NameColumn, QHeaderView::ResizeToContents);
  this->Ends->verticalHeader()->setVisible(false);
  this->Ends->setMinimumHeight(110);
  this->Ends->setToolTip("Edit a name, an extension or where the end is cut (or drag the end's "
                         "disc in the 3D view), then Prepare for CFD");
  prepareLayout->addWidget(this->Ends);
  this->Prepare = new QPushButton("Prepare for CFD", prepare);
  this->Prepare->setObjectName("prepareButton");
  this->Prepare->setToolTip("Clip the ends, name them (the largest is the inlet), add flow "
                            "extensions and flat labelled caps");
  prepareLayout->addWidget(this->Prepare);
  connect(this->Prepare, &QPushButton::clicked, this, &ExportPanel::prepareRequested);
  connect(this->Ends,
    &QTableWidget::cellChanged,
    this,
    [this](int row, int column) { this->endEdited(row, column); });
  for (QDoubleSpinBox* box : { this->InletFactor, this->OutletFactor })
  {
    connect(box,
      QOverload<double>::of(&QDoubleSpinBox::valueChanged),
      this,
      &ExportPanel::defaultFactorsChanged);
  }
  layout->addWidget(prepare);

  this->Form = new ExportOptionsForm(this);
  layout->addWidget(this->Form);
  layout->addWidget(ActionButton(actions->Check, this, "checkButton"));
  layout->addWidget(ActionButton(actions->Export, this, "exportButton"));
  this->Report = new QPlainTextEdit(this);
  this->Report->setObjectName("checkReport");
  this->Report->setReadOnly(true);
  layout->addWidget(this->Report, 1);
}

std::array<double, 3> ExportPanel::rowPosition(const EndRow& row) const
{
  if (!this->BeforePrepare)
  {
    return row.prepared.clipCentre;
  }
  return bender::ClipPlaneAt(row.path, std::max(0.0, row.distance)).centre;
}

bender::PrepareForCfdOptions ExportPanel::prepareOptions() const
{
  bender::PrepareForCfdOptions options;
  options.clip = this->Clip->isChecked();
  options.inletExtension = this->InletFactor->value();
  options.outletExtension = this->OutletFactor->value();
  // Before Prepare, what was edited; after, every end as listed (Prepare again makes the same
  // ends with the edits). Names and factors go by where the end is cut, cuts by the end.
  for (int row = 0; row < this->Ends->rowCount() && row < static_cast<int>(this->Rows.size());
       ++row)
  {
    const EndRow& end = this->Rows[static_cast<std::size_t>(row)];
    const std::array<double, 3> position = this->rowPosition(end);
    const QTableWidgetItem* name = this->Ends->item(row, NameColumn);
    const QTableWidgetItem* factor = this->Ends->item(row, FactorColumn);
    if (!this->BeforePrepare || end.nameEdited)
    {
      bender::CfdEndName entry;
      entry.position = position;
      entry.name = name ? name->text().trimmed().toStdString() : end.autoName;
      entry.inlet = end.inlet;
      options.names.push_back(entry);
    }
    bool ok = false;
    const double value = factor ? factor->text().toDouble(&ok) : 0.0;
    if (ok && (!this->BeforePrepare || end.factorEdited))
    {
      options.extensionFactors.push_back({ position, value });
    }
    if (options.clip && end.distance >= 0 && (!this->BeforePrepare || end.distanceChosen))
    {
      const std::array<double, 3> at =
        this->BeforePrepare ? end.path.position : end.prepared.centerlineEnd;
      options.ends.push_back({ at, end.distance });
    }
  }
  return options;
}

void ExportPanel::fillRow(int row)
{
  const EndRow& end = this->Rows[static_cast<std::size_t>(row)];
  const bool filling = this->Filling;
  this->Filling = true;
  auto fixed = [](const QString& text)
  {
    auto* item = new QTableWidgetItem(text);
    item->setFlags(item->flags() & ~Qt::ItemIsEditable);
    return item;
  };
  const bender::CfdEnd& prepared = end.prepared;
  double radius = prepared.radius;
  double factor = prepared.radius > 0 ? prepared.extensionLength / prepared.radius : 0.0;
  if (this->BeforePrepare)
  {
    radius = bender::ClipPlaneAt(end.path, std::max(0.0, end.distance)).radius;
    factor = end.inlet ? this->InletFactor->value() : this->OutletFactor->value();
  }
  if (!end.nameEdited || !this->Ends->item(row, NameColumn))
  {
    this->Ends->setItem(
      row, NameColumn, new QTableWidgetItem(QString::fromStdString(end.autoName)));
  }
  this->Ends->setItem(row, RoleColumn, fixed(end.inlet ? "inlet" : "outlet"));
  this->Ends->setItem(row, RadiusColumn, fixed(QString::number(radius, 'f', 2)));
  if (!end.factorEdited || !this->Ends->item(row, FactorColumn))
  {
    this->Ends->setItem(row, FactorColumn, new QTableWidgetItem(QString::number(factor, 'f', 1)));
  }
  if (end.distance >= 0)
  {
    auto* cut = new QTableWidgetItem(QString::number(end.distance, 'f', 2));
    cut->setToolTip(QString("0 to %1 mm; %2")
                      .arg(end.maximumDistance, 0, 'f', 1)
                      .arg(end.distanceChosen ? "chosen" : "default: where the radius settles"));
    this->Ends->setItem(row, CutColumn, cut);
  }
  else
  {
    this->Ends->setItem(row, CutColumn, fixed("not clipped"));
  }
  this->Filling = filling;
}

void ExportPanel::showEnds(const std::vector<bender::CfdEnd>& ends)
{
  const QSignalBlocker block(this->Ends);
  this->BeforePrepare = false;
  this->Rows.clear();
  for (const bender::CfdEnd& end : ends)
  {
    EndRow row;
    row.prepared = end;
    row.autoName = end.name;
    row.inlet = end.type == bender::PatchType::Inlet;
    row.distance = end.clipDistance;
    row.maximumDistance = 1e9;
    this->Rows.push_back(row);
  }
  this->Ends->setRowCount(static_cast<int>(this->Rows.size()));
  for (int row = 0; row < static_cast<int>(this->Rows.size()); ++row)
  {
    this->fillRow(row);
  }
}

void ExportPanel::showCenterlineEnds(const std::vector<bender::CenterlineEndPath>& paths)
{
  const QSignalBlocker block(this->Ends);
  this->BeforePrepare = true;
  this->Rows.clear();
  // The names Prepare gives: the largest end is the inlet, the others outlet_1, ... by
  // decreasing size (predicted from the inscribed radius at the cut).
  std::vector<double> radius;
  for (const bender::CenterlineEndPath& path : paths)
  {
    EndRow row;
    row.path = path;
    row.distance = std::clamp(path.defaultDistance, 0.0, path.maximumDistance);
    row.maximumDistance = path.maximumDistance;
    radius.push_back(bender::ClipPlaneAt(path, row.distance).radius);
    this->Rows.push_back(row);
  }
  std::vector<std::size_t> order(paths.size());
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    order[k] = k;
  }
  std::stable_sort(order.begin(),
    order.end(),
    [&radius](std::size_t a, std::size_t b) { return radius[a] > radius[b]; });
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    EndRow& row = this->Rows[order[k]];
    row.inlet = k == 0;
    row.autoName = k == 0 ? "inlet" : "outlet_" + std::to_string(k);
  }
  this->Ends->setRowCount(static_cast<int>(this->Rows.size()));
  for (int row = 0; row < static_cast<int>(this->Rows.size()); ++row)
  {
    this->fillRow(row);
  }
}

void ExportPanel::clearEnds()
{
  this->Rows.clear();
  this->BeforePrepare = false;
  this->Ends->setRowCount(0);
}

void ExportPanel::setCutDistance(int row, double distance)
{
  if (row < 0 || row >= static_cast<int>(this->Rows.size()) || !std::isfinite(distance))
  {
    return;
  }
  EndRow& end = this->Rows[static_cast<std::size_t>(row)];
  if (end.distance < 0)
  {
    return;
  }
  end.distance = std::clamp(distance, 0.0, end.maximumDistance);
  end.distanceChosen = true;
  const QSignalBlocker block(this->Ends);
  this->fillRow(row);
}

double ExportPanel::cutDistance(int row) const
{
  return row >= 0 && row < static_cast<int>(this->Rows.size())
    ? this->Rows[static_cast<std::size_t>(row)].distance
    : -1.0;
}

QString ExportPanel::endName(int row) const
{
  const QTableWidgetItem* item =
    row >= 0 && row < this->Ends->rowCount() ? this->Ends->item(row, NameColumn) : nullptr;
  return item ? item->text().trimmed() : QString();
}

bool ExportPanel::endIsInlet(int row) const
{
  return row >= 0 && row < static_cast<int>(this->Rows.size()) &&
    (this->Rows[static_cast<std::size_t>(row)].inlet || this->endName(row) == "inlet");
}

void ExportPanel::endEdited(int row, int column)
{
  if (this->Filling || row < 0 || row >= static_cast<int>(this->Rows.size()))
  {
    return;
  }
  EndRow& end = this->Rows[static_cast<std::size_t>(row)];
  if (column == NameColumn)
  {
    end.nameEdited = true;
    emit this->endNamesChanged();
  }
  else if (column == FactorColumn)
  {
    end.factorEdited = true;
  }
  else if (column == CutColumn && end.distance >= 0)
  {
    const QTableWidgetItem* item = this->Ends->item(row, CutColumn);
    bool ok = false;
    const double value = item ? item->text().trimmed().toDouble(&ok) : 0.0;
    if (ok && std::isfinite(value))
    {
      end.distance = std::clamp(value, 0.0, end.maximumDistance);
      end.distanceChosen = true;
    }
    // Shown as taken (clamped, or the previous value for text that is no number).
    const QSignalBlocker block(this->Ends);
    this->fillRow(row);
    if (ok)
    {
      emit this->cutDistanceEdited(row, end.distance);
    }
  }
}

void ExportPanel::defaultFactorsChanged()
{
  // Before Prepare the factors not edited follow the defaults.
  if (!this->BeforePrepare)
  {
    return;
  }
  const QSignalBlocker block(this->Ends);
  for (int row = 0; row < static_cast<int>(this->Rows.size()); ++row)
  {
    this->fillRow(row);
  }
}

void ExportPanel::showEvent(QShowEvent* event)
{
  QWidget::showEvent(event);
  emit this->shownChanged(true);
}

void ExportPanel::hideEvent(QHideEvent* event)
{
  QWidget::hideEvent(event);
  emit this->shownChanged(false);
}

bender::ExportSurfaceOptions ExportPanel::options(const QString& path) const
{
  return this->Form->options(path);
}

void ExportPanel::showReport(const QString& text)
{
  this->Report->setPlainText(text);
}

QString ExportPanel::fileFilter()
{
  return QString::fromStdString(bender::MeshFileDialogFilters(bender::MeshAccess::Write));
}
