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
  this->Formats->addItems({ "STL (binary)",
    "STL (ASCII)",
    "VTP (keeps the patch labels)",
    "PLY",
    "OBJ",
    "TetGen (.smesh, facet markers)" });
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
    this->Formats->setCurrentIndex(StlAscii);
    this->Patches->setCurrentIndex(1);
  }
  else
  {
    this->Formats->setCurrentIndex(TetgenSmesh);
    this->Patches->setCurrentIndex(0);
  }
  this->Note->clear();
  this->Applying = false;
  const QSignalBlocker block(this->Presets);
  this->Presets->setCurrentIndex(preset);
}

void ExportOptionsForm::formatChanged()
{
  const int format = this->Formats->currentIndex();
  const bool stl = format == StlBinary || format == StlAscii;
  this->Patches->setEnabled(stl);
  if (format == StlBinary && this->Patches->currentIndex() == 1)
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
  if (this->Patches->currentIndex() == 1 && this->Formats->currentIndex() == StlBinary)
  {
    const QSignalBlocker block(this->Formats);
    this->Formats->setCurrentIndex(StlAscii);
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
  switch (this->Formats->currentIndex())
  {
    case Vtp:
      return ".vtp";
    case Ply:
      return ".ply";
    case Obj:
      return ".obj";
    case TetgenSmesh:
      return ".smesh";
    default:
      return ".stl";
  }
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
  const bool stlPath = path.toLower().endsWith(".stl");
  options.stlEncoding = (stlPath && this->Formats->currentIndex() == StlAscii)
    ? bender::StlEncoding::Ascii
    : bender::StlEncoding::Binary;
  options.cap = this->Cap->isChecked();
  const int patches = stlPath ? this->Patches->currentIndex() : 0;
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
  this->Ends = new QTableWidget(0, 4, prepare);
  this->Ends->setObjectName("endsTable");
  this->Ends->setHorizontalHeaderLabels({ "Name", "Role", "Radius (mm)", "Extension (x r)" });
  this->Ends->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  this->Ends->verticalHeader()->setVisible(false);
  this->Ends->setMinimumHeight(90);
  this->Ends->setToolTip("Edit a name or an extension, then Prepare for CFD again");
  prepareLayout->addWidget(this->Ends);
  this->Prepare = new QPushButton("Prepare for CFD", prepare);
  this->Prepare->setObjectName("prepareButton");
  this->Prepare->setToolTip("Clip the ends, name them (the largest is the inlet), add flow "
                            "extensions and flat labelled caps");
  prepareLayout->addWidget(this->Prepare);
  connect(this->Prepare, &QPushButton::clicked, this, &ExportPanel::prepareRequested);
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

bender::PrepareForCfdOptions ExportPanel::prepareOptions() const
{
  bender::PrepareForCfdOptions options;
  options.Clip = this->Clip->isChecked();
  options.InletExtension = this->InletFactor->value();
  options.OutletExtension = this->OutletFactor->value();
  // The listed ends, by the centre of their own rim: names and factors as edited.
  for (int row = 0; row < this->Ends->rowCount() && row < static_cast<int>(this->Listed.size());
       ++row)
  {
    const bender::CfdEnd& end = this->Listed[static_cast<std::size_t>(row)];
    const QTableWidgetItem* name = this->Ends->item(row, 0);
    const QTableWidgetItem* factor = this->Ends->item(row, 3);
    bender::CfdEndName entry;
    entry.Position = end.ClipCentre;
    entry.Name = name ? name->text().trimmed().toStdString() : end.Name;
    entry.Inlet = end.Type == bender::PatchType::Inlet;
    options.Names.push_back(entry);
    bool ok = false;
    const double value = factor ? factor->text().toDouble(&ok) : 0.0;
    if (ok)
    {
      options.ExtensionFactors.push_back({ end.ClipCentre, value });
    }
  }
  return options;
}

void ExportPanel::showEnds(const std::vector<bender::CfdEnd>& ends)
{
  this->Listed = ends;
  this->Ends->setRowCount(static_cast<int>(ends.size()));
  for (int row = 0; row < static_cast<int>(ends.size()); ++row)
  {
    const bender::CfdEnd& end = ends[static_cast<std::size_t>(row)];
    auto* role = new QTableWidgetItem(bender::PatchTypeName(end.Type));
    role->setFlags(role->flags() & ~Qt::ItemIsEditable);
    auto* radius = new QTableWidgetItem(QString::number(end.Radius, 'f', 2));
    radius->setFlags(radius->flags() & ~Qt::ItemIsEditable);
    const double factor = end.Radius > 0 ? end.ExtensionLength / end.Radius : 0.0;
    this->Ends->setItem(row, 0, new QTableWidgetItem(QString::fromStdString(end.Name)));
    this->Ends->setItem(row, 1, role);
    this->Ends->setItem(row, 2, radius);
    this->Ends->setItem(row, 3, new QTableWidgetItem(QString::number(factor, 'f', 1)));
  }
}

void ExportPanel::clearEnds()
{
  this->Listed.clear();
  this->Ends->setRowCount(0);
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
  return "STL (*.stl);;VTK XML polydata with patch labels (*.vtp);;TetGen surface mesh "
         "(*.smesh);;PLY (*.ply);;Wavefront OBJ (*.obj)";
}
