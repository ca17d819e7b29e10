#include "TetgenExport.h"

#include "FileUtilities.h"
#include "StringUtil.h"

#include <vtkPolyData.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <memory>
#include <unordered_map>

namespace bender
{

bool TetgenFormatForPath(const std::string& path, TetgenFormat& format)
{
  const std::string ext = LowerExtension(path);
  if (ext == ".smesh")
  {
    format = TetgenFormat::Smesh;
    return true;
  }
  if (ext == ".poly")
  {
    format = TetgenFormat::Poly;
    return true;
  }
  return false;
}

namespace
{
void AppendLine(std::string& text, const char* format, ...) __attribute__((format(printf, 2, 3)));

void AppendLine(std::string& text, const char* format, ...)
{
  char line[512];
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(line, sizeof(line), format, args);
  va_end(args);
  text.append(line, static_cast<std::size_t>(std::min<int>(n, sizeof(line) - 1)));
}
} // namespace

std::string TetgenText(const LabelledSurface& mesh,
  TetgenFormat format,
  const ExportTransform& transform,
  const double* insidePoint)
{
  const LabelledTriangles labels = CollectLabelledTriangles(mesh);
  // Nodes: the points of triangles, numbered from 1 in order of first use.
  std::unordered_map<vtkIdType, long long> node;
  std::vector<vtkIdType> order;
  for (const auto& tri : labels.triangles)
  {
    for (vtkIdType id : tri)
    {
      if (node.emplace(id, static_cast<long long>(order.size()) + 1).second)
      {
        order.push_back(id);
      }
    }
  }
  std::string text;
  text.reserve(order.size() * 64 + labels.triangles.size() * 40 + 1024);
  AppendLine(text,
    "# %s written by bender: frame %s, unit %s\n",
    format == TetgenFormat::Smesh ? "TetGen .smesh" : "TetGen .poly",
    StlFrameName(transform.Frame()),
    transform.Unit().c_str());
  text += "# facet markers are CellEntityIds:";
  for (const PatchLabel& patch : labels.patches)
  {
    AppendLine(text, " %d=%s", patch.id, patch.name.c_str());
  }
  text += "\n# part 1: nodes\n";
  AppendLine(text, "%lld 3 0 0\n", static_cast<long long>(order.size()));
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    double in[3], p[3];
    mesh.surface->GetPoint(order[k], in);
    transform.Apply(in, p);
    AppendLine(text, "%lld %.17g %.17g %.17g\n", static_cast<long long>(k) + 1, p[0], p[1], p[2]);
  }
  text += "# part 2: facets with boundary markers\n";
  AppendLine(text, "%lld 1\n", static_cast<long long>(labels.triangles.size()));
  for (std::size_t t = 0; t < labels.triangles.size(); ++t)
  {
    const auto& tri = labels.triangles[t];
    const int marker = labels.patches[labels.patch[t]].id;
    if (format == TetgenFormat::Smesh)
    {
      AppendLine(
        text, "3 %lld %lld %lld %d\n", node.at(tri[0]), node.at(tri[1]), node.at(tri[2]), marker);
    }
    else
    {
      AppendLine(text,
        "1 0 %d\n3 %lld %lld %lld\n",
        marker,
        node.at(tri[0]),
        node.at(tri[1]),
        node.at(tri[2]));
    }
  }
  text += "# part 3: holes\n0\n# part 4: regions\n";
  if (insidePoint)
  {
    AppendLine(text, "1\n1 %.17g %.17g %.17g 1\n", insidePoint[0], insidePoint[1], insidePoint[2]);
  }
  else
  {
    text += "0\n";
  }
  return text;
}

AtomicFile TetgenFile(const LabelledSurface& mesh,
  const std::string& path,
  TetgenFormat format,
  const ExportTransform& transform,
  const double* insidePoint)
{
  std::shared_ptr<const std::string> text;
  try
  {
    text = std::make_shared<const std::string>(TetgenText(mesh, format, transform, insidePoint));
  }
  catch (const StlExportError& e)
  {
    throw StlExportError(DisplayName(path) + ": " + e.what());
  }
  return { path, TextProducer(text) };
}

AtomicFile TetgenFile(vtkPolyData* mesh,
  const std::string& path,
  TetgenFormat format,
  const ExportTransform& transform,
  const double* insidePoint)
{
  return TetgenFile(ReadExportLabels(mesh, path), path, format, transform, insidePoint);
}

} // namespace bender
