#include "ExportPanel.h"

#include "MainActions.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QLabel>
#include <QPlainTextEdit>
#include <QToolButton>
#include <QVBoxLayout>

ExportPanel::ExportPanel(MainActions* actions, QWidget* parent)
  : QWidget(parent)
{
  auto* layout = new QVBoxLayout(this);
  auto* form = new QFormLayout;
  layout->addLayout(form);
  this->Format = new QComboBox(this);
  this->Format->setObjectName("formatCombo");
  this->Format->addItems({ "STL (binary)", "STL (ASCII)", "VTP", "PLY", "OBJ" });
  form->addRow("Format", this->Format);
  this->Cap = new QCheckBox("Cap the open vessel ends (inlets and outlets)", this);
  this->Cap->setObjectName("capCheck");
  form->addRow("Caps", this->Cap);
  this->Patches = new QComboBox(this);
  this->Patches->setObjectName("patchesCombo");
  this->Patches->addItems(
    { "One surface", "Named solids per patch (ASCII, snappyHexMesh)", "One STL file per patch" });
  form->addRow("STL patches", this->Patches);
  this->Frame = new QComboBox(this);
  this->Frame->setObjectName("frameCombo");
  this->Frame->addItems({ "LPS (DICOM, ITK)", "RAS (Slicer, NIfTI)" });
  form->addRow("Frame", this->Frame);
  form->addRow("Unit", new QLabel("millimetres (frame and unit stated in the file header)", this));
  layout->addWidget(ActionButton(actions->Check, this, "checkButton"));
  layout->addWidget(ActionButton(actions->Export, this, "exportButton"));
  this->Report = new QPlainTextEdit(this);
  this->Report->setObjectName("checkReport");
  this->Report->setReadOnly(true);
  layout->addWidget(this->Report, 1);
}

bender::ExportSurfaceOptions ExportPanel::options(const QString& path) const
{
  bender::ExportSurfaceOptions options;
  options.output = path.toStdString();
  options.stlEncoding = (path.toLower().endsWith(".stl") && this->Format->currentIndex() == 1)
    ? bender::StlEncoding::Ascii
    : bender::StlEncoding::Binary;
  options.cap = this->Cap->isChecked();
  const int patches = this->Patches->currentIndex();
  options.patches = patches == 1
    ? bender::StlPatchMode::Solids
    : (patches == 2 ? bender::StlPatchMode::Files : bender::StlPatchMode::Single);
  options.frame = this->Frame->currentIndex() == 1 ? bender::StlFrame::RAS : bender::StlFrame::LPS;
  return options;
}

void ExportPanel::showReport(const QString& text)
{
  this->Report->setPlainText(text);
}

QString ExportPanel::fileFilter()
{
  return "STL (*.stl);;VTK XML polydata (*.vtp);;PLY (*.ply);;Wavefront OBJ (*.obj)";
}
