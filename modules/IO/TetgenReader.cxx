#include "TetgenReader.h"

#include "InputValidation.h"
#include "PatchLabels.h"
#include "StringUtil.h"
#include "VtkMessageGuard.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

namespace bender
{
namespace io_detail
{

namespace
{

// The data lines of a TetGen file ("#" starts a comment), as words, with their line numbers.
class TetgenLines
{
public:
  TetgenLines(const std::string& path)
    : Path(path)
    , In(path, std::ios::binary)
  {
    if (!this->In)
    {
      FailMesh(path, "cannot read the file");
    }
  }

  // The next data line's words; fails at the end of the file, saying what was expected.
  const std::vector<std::string>& Next(const char* expected)
  {
    std::string line;
    while (std::getline(this->In, line))
    {
      ++this->Number;
      const std::size_t hash = line.find('#');
      std::istringstream words(line.substr(0, hash));
      this->Words.clear();
      for (std::string word; words >> word;)
      {
        this->Words.push_back(word);
      }
      if (!this->Words.empty())
      {
        return this->Words;
      }
    }
    FailMesh(this->Path, std::string("the file ends where ") + expected + " should be");
  }

  [[noreturn]] void Fail(const std::string& problem) const
  {
    FailMesh(this->Path, "line " + std::to_string(this->Number) + ": " + problem);
  }

  // Word k of the current line as an integer in [low, high].
  long long Integer(std::size_t k, long long low, long long high, const char* what) const
  {
    long long value = 0;
    if (k >= this->Words.size())
    {
      this->Fail(std::string("expected ") + what);
    }
    const std::string& word = this->Words[k];
    const auto result = std::from_chars(word.data(), word.data() + word.size(), value);
    if (result.ec != std::errc() || result.ptr != word.data() + word.size() || value < low ||
      value > high)
    {
      this->Fail(std::string("expected ") + what + " from " + std::to_string(low) + " to " +
        std::to_string(high) + ", found \"" + QuoteBytes(word) + "\"");
    }
    return value;
  }

  double Real(std::size_t k, const char* what) const
  {
    if (k >= this->Words.size())
    {
      this->Fail(std::string("expected ") + what);
    }
    char* end = nullptr;
    const double value = std::strtod(this->Words[k].c_str(), &end);
    if (end != this->Words[k].c_str() + this->Words[k].size() || !std::isfinite(value))
    {
      this->Fail(std::string("expected a finite ") + what + ", found \"" +
        QuoteBytes(this->Words[k]) + "\"");
    }
    return value;
  }

private:
  std::string Path;
  std::ifstream In;
  std::vector<std::string> Words;
  long long Number = 0;
};

} // namespace

vtkSmartPointer<vtkPolyData> ReadTetgenMesh(const std::string& path, std::uintmax_t size)
{
  // Every node and facet takes a line of at least 2 bytes: counts beyond that are corrupt.
  const auto most = static_cast<long long>(size / 2 + 1);
  TetgenLines lines(path);
  lines.Next("the node count (part 1)");
  const long long nodes = lines.Integer(0, 0, most, "the number of nodes");
  if (nodes == 0)
  {
    lines.Fail("the nodes are in a separate .node file, which is not read; export the surface "
               "with its nodes (bender-cli export OUT.smesh)");
  }
  lines.Integer(1, 3, 3, "the dimension");
  const long long attributes = lines.Integer(2, 0, 1000, "the number of node attributes");
  const long long nodeMarkers = lines.Integer(3, 0, 1, "the node marker flag (0 or 1)");
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(nodes);
  long long first = 0;
  for (long long i = 0; i < nodes; ++i)
  {
    const auto& words = lines.Next("a node");
    const long long index = lines.Integer(0, 0, most, "the node number");
    if (i == 0)
    {
      first = index; // numbered from 0 or from 1, as the first node says
    }
    if (index != first + i)
    {
      lines.Fail("node " + std::to_string(index) + " out of order (expected " +
        std::to_string(first + i) + ")");
    }
    if (static_cast<long long>(words.size()) < 4 + attributes + nodeMarkers)
    {
      lines.Fail("a node needs its number, 3 coordinates, " + std::to_string(attributes) +
        " attributes and " + std::to_string(nodeMarkers) + " marker");
    }
    points->SetPoint(i, lines.Real(1, "x"), lines.Real(2, "y"), lines.Real(3, "z"));
  }
  const bool poly = LowerExtension(path) == ".poly";
  lines.Next("the facet count (part 2)");
  const long long facets = lines.Integer(0, 0, most, "the number of facets");
  const bool markers = lines.Integer(1, 0, 1, "the facet marker flag (0 or 1)") == 1;
  vtkNew<vtkCellArray> polygons;
  vtkNew<vtkIntArray> ids;
  ids->SetName(kCellEntityIdsArrayName);
  const auto polygon = [&]()
  {
    const auto& words = lines.Next("a polygon");
    const long long corners = lines.Integer(0, 3, nodes, "the number of corners");
    if (static_cast<long long>(words.size()) < 1 + corners)
    {
      lines.Fail("a polygon of " + std::to_string(corners) + " corners lists fewer");
    }
    std::vector<vtkIdType> cell;
    for (long long k = 1; k <= corners; ++k)
    {
      cell.push_back(static_cast<vtkIdType>(
        lines.Integer(static_cast<std::size_t>(k), first, first + nodes - 1, "a node number") -
        first));
    }
    polygons->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
    return corners;
  };
  for (long long f = 0; f < facets; ++f)
  {
    long long marker = kWallEntityId;
    if (poly)
    {
      // A facet: "<polygons> [holes] [marker]", its polygons, then its hole points.
      const std::size_t given = lines.Next("a facet").size();
      const long long count = lines.Integer(0, 1, most, "the number of polygons");
      const long long holes = given > 1 ? lines.Integer(1, 0, most, "the number of holes") : 0;
      if (markers && given > 2)
      {
        marker = lines.Integer(2, -(1 << 30), 1 << 30, "the facet's boundary marker");
      }
      for (long long p = 0; p < count; ++p)
      {
        polygon();
        ids->InsertNextValue(static_cast<int>(marker));
      }
      for (long long h = 0; h < holes; ++h)
      {
        lines.Next("a facet hole");
      }
      continue;
    }
    const long long corners = polygon();
    if (markers)
    {
      marker = lines.Integer(static_cast<std::size_t>(corners) + 1,
        -(1 << 30),
        1 << 30,
        "the facet's boundary marker after its corners");
    }
    ids->InsertNextValue(static_cast<int>(marker));
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polygons);
  // The markers Bender writes are patch ids (>= 1): kept as the patch labels' CellEntityIds.
  double range[2] = { 0.0, 0.0 };
  ids->GetRange(range);
  if (markers && ids->GetNumberOfTuples() > 0 && range[0] >= kWallEntityId)
  {
    mesh->GetCellData()->AddArray(ids);
  }
  return mesh;
}

} // namespace io_detail
} // namespace bender
