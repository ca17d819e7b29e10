#include "FlowReport.h"

#include "AtomicFile.h"
#include "BenderErrors.h"
#include "ReportLayout.h"
#include "StringUtil.h"

#include <QDateTime>
#include <QGuiApplication>
#include <QPageLayout>
#include <QPageSize>
#include <QPainter>
#include <QPdfWriter>

#include <vtkImageData.h>

#include <cstdio>
#include <filesystem>

namespace bender
{
namespace
{
// QPainter needs a QGuiApplication for its fonts. bender-cli has none: make one, on the
// offscreen platform unless QT_QPA_PLATFORM says otherwise. It lives as long as the process
// (never deleted: Qt's fonts may be used until exit).
void EnsureGuiApplication()
{
  if (QCoreApplication::instance())
  {
    return;
  }
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM"))
  {
    qputenv("QT_QPA_PLATFORM", "offscreen");
  }
  // Qt's platform remarks (no XDG_RUNTIME_DIR, ...) are not bender-cli's to print; its
  // critical and fatal messages still are.
  qInstallMessageHandler(
    [](QtMsgType type, const QMessageLogContext&, const QString& message)
    {
      if (type == QtCriticalMsg || type == QtFatalMsg)
      {
        std::fprintf(stderr, "%s\n", message.toLocal8Bit().constData());
      }
    });
  static int argc = 1;
  static char name[] = "bender-report";
  static char* argv[] = { name, nullptr };
  new QGuiApplication(argc, argv);
}

QString Q(const std::string& text)
{
  return QString::fromStdString(text);
}

// VTK's image (RGB or RGBA, rows from the bottom) as a QImage.
QImage ToQImage(vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  const int components = image->GetNumberOfScalarComponents();
  const auto* data = static_cast<const unsigned char*>(image->GetScalarPointer());
  const QImage view(data,
    dims[0],
    dims[1],
    dims[0] * components,
    components == 4 ? QImage::Format_RGBA8888 : QImage::Format_RGB888);
  return view.mirrored(false, true);
}

std::string Number(const std::optional<double>& value, int decimals)
{
  return FormatCfdValue(value, decimals);
}

void Provenance(ReportLayout& layout,
  const CfdCaseComparison& c,
  const std::string& version,
  const std::string& date)
{
  layout.Heading("Flow comparison: " + Q(c.a.label) + " and " + Q(c.b.label), 17);
  layout.Paragraph(Q("A: " + c.a.label + ", case " + c.a.directory + "\nB: " + c.b.label +
                     ", case " + c.b.directory),
    9.5);
  layout.Paragraph(Q("Bender " + version + ", " + date +
                     ". Steady laminar CFD (OpenFOAM simpleFoam); pressures relative to the "
                     "outlets' mean, wall shear stress in Pa."),
    8.5,
    QColor(90, 90, 90));
}

void Plan(ReportLayout& layout, const CfdCaseComparison& c)
{
  layout.Heading("The plan", 12.5);
  if (!c.plan)
  {
    layout.Paragraph("No plan given: the plan's description and warps are not reported.");
  }
  else
  {
    layout.Paragraph(Q(DisplayName(c.plan->file) + (c.plan->name.empty() ? "" : ": ") +
      c.plan->name + (c.plan->preparedForCfd ? " (with a Prepare for CFD step)" : "")));
    std::vector<ReportRow> rows{
      { { "warp", "ribbon end turned (deg)", "ribbon length change (%)", "R (mm)" } }
    };
    for (size_t i = 0; i < c.plan->warps.size(); ++i)
    {
      const PlanWarpMeasures& w = c.plan->warps[i];
      rows.push_back({ { QString::number(i + 1),
        QString::number(w.endTurn, 'f', 1),
        QString::number(w.lengthChange * 100.0, 'f', 1),
        QString::number(w.radius, 'f', 2) } });
    }
    layout.Table(rows, { 0.25, 0.25, 0.25, 0.25 });
  }
  layout.Heading("Bend measures (centerlines of both shapes)", 12.5);
  if (c.bends.empty())
  {
    layout.Paragraph("Not measured (see below).");
    return;
  }
  layout.Paragraph("Each branch of the centerlines, named by the ends it leads to: its bend "
                   "angle (between its end directions, degrees), its length (mm) and its "
                   "minimal inscribed radius (mm), in A and in B.",
    8.5,
    QColor(90, 90, 90));
  std::vector<ReportRow> rows{
    { { "branch", "angle A", "angle B", "length A", "length B", "r min A", "r min B" } }
  };
  for (const BendBranchMeasures& m : c.bends)
  {
    rows.push_back({ { Q(m.name),
      Q(Number(m.angleA, 1)),
      Q(Number(m.angleB, 1)),
      Q(Number(m.lengthA, 1)),
      Q(Number(m.lengthB, 1)),
      Q(Number(m.minRadiusA, 2)),
      Q(Number(m.minRadiusB, 2)) } });
  }
  layout.Table(rows, { 0.34, 0.11, 0.11, 0.11, 0.11, 0.11, 0.11 });
}

void Comparison(ReportLayout& layout, const CfdCaseComparison& c)
{
  layout.Heading("Comparison (B - A; highlighted: notable differences)", 12.5, 400);
  std::vector<ReportRow> rows{
    { { "quantity", Q("A: " + c.a.label), Q("B: " + c.b.label), "B - A", "relative" } }
  };
  for (const CfdComparisonRow& row : c.table.rows)
  {
    const int decimals = CfdRowDecimals(row);
    const bool run = row.kind == CfdRowKind::Run;
    rows.push_back(
      { { Q(row.label + (row.unit.empty() ? "" : " (" + row.unit + ")")),
          Q(row.textA.empty() ? Number(row.a, decimals) : row.textA),
          Q(row.textB.empty() ? Number(row.b, decimals) : row.textB),
          run ? QString() : Q(Number(row.difference, decimals)),
          row.relative && !run ? Q(Number(*row.relative * 100.0, 1) + " %") : QString() },
        row.highlighted });
  }
  layout.Table(rows, { 0.38, 0.18, 0.18, 0.13, 0.13 });
  layout.Paragraph(Q(DescribeHighlightRule(c.table.rule) + "."), 8, QColor(90, 90, 90));
  for (const CfdComparisonRow& row : c.table.rows)
  {
    if (row.highlighted && !row.note.empty())
    {
      layout.Paragraph(Q(row.label + ": " + row.note + "."), 8.5);
    }
  }
  for (const std::string& note : c.table.notes)
  {
    layout.Paragraph(Q("Note: " + note + "."), 8.5);
  }
}

void MeshAndConvergence(ReportLayout& layout, const CfdCaseComparison& c)
{
  layout.Heading("Mesh and convergence", 12.5, 300);
  for (const ComparedCfdCase* one : { &c.a, &c.b })
  {
    std::string text = (one == &c.a ? "A: " : "B: ") + one->label + ". ";
    for (const std::string& line : CfdMeshAndConvergenceLines(one->results))
    {
      text += line + ". ";
    }
    layout.Paragraph(Q(text), 9);
  }
  if (!c.unavailable.empty())
  {
    layout.Heading("Not available", 11);
    for (const std::string& line : c.unavailable)
    {
      layout.Paragraph(Q(line + "."), 8.5, QColor(120, 60, 0));
    }
  }
}

std::string Now()
{
  return QDateTime::currentDateTimeUtc().toString("yyyy-MM-dd HH:mm 'UTC'").toStdString();
}
} // namespace

std::string BenderVersion()
{
  return BENDER_VERSION;
}

FlowReportResult WriteFlowReport(const CfdCaseComparison& comparison,
  const FlowReportOptions& options)
{
  if (options.output.empty())
  {
    throw InputError("report: no output file given");
  }
  const std::vector<FlowPicture> pictures = RenderFlowPictures(comparison, options.pictures);
  FlowReportResult result;
  result.pdf = options.output;
  if (!options.pngFolder.empty())
  {
    std::error_code ec;
    std::filesystem::create_directories(options.pngFolder, ec);
    if (!std::filesystem::is_directory(options.pngFolder))
    {
      throw InputError(options.pngFolder + ": cannot make the folder for the pictures");
    }
    for (const FlowPicture& picture : pictures)
    {
      const std::string path =
        (std::filesystem::path(options.pngFolder) / (picture.name + ".png")).string();
      WritePng(picture.image, path);
      result.pngs.push_back(path);
    }
  }

  EnsureGuiApplication();
  const std::string version = options.version.empty() ? BenderVersion() : options.version;
  const std::string date = options.date.empty() ? Now() : options.date;
  std::string problem;
  const bool written = AtomicWrite(
    options.output,
    [&](const std::string& tempPath, std::string& why)
    {
      QPdfWriter writer(Q(tempPath));
      writer.setResolution(300);
      writer.setPageSize(QPageSize(QPageSize::A4));
      writer.setPageMargins(QMarginsF(16, 14, 16, 14), QPageLayout::Millimeter);
      writer.setTitle(
        Q("Bender flow comparison: " + comparison.a.label + " and " + comparison.b.label));
      writer.setCreator(Q("Bender " + version));
      QPainter painter;
      if (!painter.begin(&writer))
      {
        why = "cannot write a PDF there";
        return false;
      }
      ReportLayout layout(writer, painter);
      Provenance(layout, comparison, version, date);
      Comparison(layout, comparison);
      Plan(layout, comparison);
      MeshAndConvergence(layout, comparison);
      for (size_t i = 0; i < pictures.size(); ++i)
      {
        // Two pictures a page: one quantity from both viewpoints.
        if (i % 2 == 0)
        {
          layout.NewPage();
        }
        layout.Picture(ToQImage(pictures[i].image), Q(pictures[i].title), Q(pictures[i].caption));
      }
      result.pages = layout.Pages();
      if (!painter.end())
      {
        why = "write failed (disk full?)";
        return false;
      }
      return true;
    },
    problem);
  if (!written)
  {
    throw InputError(options.output + ": " + problem);
  }
  return result;
}

} // namespace bender
