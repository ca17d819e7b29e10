#include "PatchLabels.h"

#include "BenderErrors.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace bender
{

const char* PatchTypeName(PatchType type)
{
  switch (type)
  {
    case PatchType::Inlet:
      return "inlet";
    case PatchType::Outlet:
      return "outlet";
    case PatchType::Wall:
    default:
      return "wall";
  }
}

PatchType PatchTypeFromName(const std::string& name)
{
  if (name == "wall")
  {
    return PatchType::Wall;
  }
  if (name == "inlet")
  {
    return PatchType::Inlet;
  }
  if (name == "outlet")
  {
    return PatchType::Outlet;
  }
  throw InputError("unknown patch type '" + name + "' (expected wall, inlet or outlet)");
}

bool IsValidPatchName(const std::string& name)
{
  if (name.empty() || name.size() > 64 || (name[0] >= '0' && name[0] <= '9'))
  {
    return false;
  }
  return std::all_of(name.begin(),
    name.end(),
    [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    });
}

bool HasPatchLabels(vtkPolyData* surface)
{
  if (!surface)
  {
    return false;
  }
  vtkCellData* cd = surface->GetCellData();
  return cd->GetArray(kCellEntityIdsArrayName) || cd->GetArray(kLegacyPatchIdArrayName);
}

std::vector<int> CellPatchIds(vtkPolyData* surface)
{
  if (!surface)
  {
    return {};
  }
  const vtkIdType cells = surface->GetNumberOfCells();
  vtkCellData* cd = surface->GetCellData();
  vtkDataArray* ids = cd->GetArray(kCellEntityIdsArrayName);
  int offset = 0;
  const char* name = kCellEntityIdsArrayName;
  if (!ids)
  {
    ids = cd->GetArray(kLegacyPatchIdArrayName);
    offset = 1;
    name = kLegacyPatchIdArrayName;
  }
  std::vector<int> out(static_cast<std::size_t>(cells), kWallEntityId);
  if (!ids)
  {
    return out;
  }
  if (ids->GetNumberOfTuples() != cells || ids->GetNumberOfComponents() != 1)
  {
    throw InputError(std::string("the cell array ") + name + " has " +
      std::to_string(ids->GetNumberOfTuples()) + " values of " +
      std::to_string(ids->GetNumberOfComponents()) + " components for " + std::to_string(cells) +
      " cells");
  }
  for (vtkIdType c = 0; c < cells; ++c)
  {
    const double v = ids->GetComponent(c, 0) + offset;
    if (!std::isfinite(v) || v != std::floor(v) || v < 1.0 || v > static_cast<double>(cells) + 1)
    {
      throw InputError(std::string("the cell array ") + name + " holds " +
        std::to_string(ids->GetComponent(c, 0)) + " at cell " + std::to_string(c) +
        " (labels are whole numbers from " + (offset ? "0" : "1") + " to the number of cells)");
    }
    out[static_cast<std::size_t>(c)] = static_cast<int>(v);
  }
  return out;
}

namespace
{
vtkStringArray* FieldStrings(vtkPolyData* surface, const char* name)
{
  return vtkStringArray::SafeDownCast(surface->GetFieldData()->GetAbstractArray(name));
}
} // namespace

std::vector<PatchLabel> ReadPatchLabels(vtkPolyData* surface)
{
  const std::vector<int> ids = CellPatchIds(surface);
  const std::set<int> present(ids.begin(), ids.end());
  vtkStringArray* names = surface ? FieldStrings(surface, kPatchNamesArrayName) : nullptr;
  vtkStringArray* types = surface ? FieldStrings(surface, kPatchTypesArrayName) : nullptr;
  const bool named = names && surface->GetCellData()->GetArray(kCellEntityIdsArrayName);
  std::vector<PatchLabel> out;
  std::set<std::string> used;
  for (int id : present)
  {
    PatchLabel label;
    label.id = id;
    const vtkIdType entry = id - 1;
    if (named && entry < names->GetNumberOfValues() && !names->GetValue(entry).empty())
    {
      label.name = names->GetValue(entry);
      if (!IsValidPatchName(label.name))
      {
        throw InputError("the patch name '" + label.name.substr(0, 64) + "' of label " +
          std::to_string(id) + " is not a valid patch name (letters, digits and _)");
      }
      label.type = id == kWallEntityId ? PatchType::Wall : PatchType::Outlet;
      if (types && entry < types->GetNumberOfValues())
      {
        label.type = PatchTypeFromName(types->GetValue(entry));
      }
    }
    else
    {
      label.name = id == kWallEntityId ? "wall" : "cap_" + std::to_string(id - 1);
      label.type = id == kWallEntityId ? PatchType::Wall : PatchType::Outlet;
    }
    if (!used.insert(label.name).second)
    {
      throw InputError("two patches are named '" + label.name + "'");
    }
    out.push_back(label);
  }
  return out;
}

void WritePatchLabels(vtkPolyData* surface,
  const std::vector<int>& cellIds,
  const std::vector<PatchLabel>& patches)
{
  if (!surface)
  {
    throw InputError("no surface to label");
  }
  const vtkIdType cells = surface->GetNumberOfCells();
  if (static_cast<vtkIdType>(cellIds.size()) != cells)
  {
    throw InputError("patch labels for " + std::to_string(cellIds.size()) +
      " cells given to a surface of " + std::to_string(cells) + " cells");
  }
  std::map<int, const PatchLabel*> byId;
  std::set<std::string> names;
  for (const PatchLabel& p : patches)
  {
    if (p.id < 1)
    {
      throw InputError("patch '" + p.name + "' has label " + std::to_string(p.id) +
        " (labels start at 1, the wall)");
    }
    if (!IsValidPatchName(p.name))
    {
      throw InputError("'" + p.name.substr(0, 64) +
        "' is not a valid patch name (1 to 64 letters, digits or _, not starting with a digit)");
    }
    if (!names.insert(p.name).second || !byId.emplace(p.id, &p).second)
    {
      throw InputError(
        "two patches share the name '" + p.name + "' or the label " + std::to_string(p.id));
    }
  }
  int maxId = 0;
  for (int id : cellIds)
  {
    if (byId.find(id) == byId.end())
    {
      throw InputError("a cell has the label " + std::to_string(id) + ", which names no patch");
    }
    maxId = std::max(maxId, id);
  }
  for (const auto& entry : byId)
  {
    maxId = std::max(maxId, entry.first);
  }
  vtkNew<vtkIntArray> entity;
  entity->SetName(kCellEntityIdsArrayName);
  entity->SetNumberOfTuples(cells);
  vtkNew<vtkIntArray> face;
  face->SetName(kModelFaceIdArrayName);
  face->SetNumberOfTuples(cells);
  for (vtkIdType c = 0; c < cells; ++c)
  {
    entity->SetValue(c, cellIds[static_cast<std::size_t>(c)]);
    face->SetValue(c, cellIds[static_cast<std::size_t>(c)]);
  }
  vtkCellData* cd = surface->GetCellData();
  cd->RemoveArray(kLegacyPatchIdArrayName);
  cd->RemoveArray(kCellEntityIdsArrayName);
  cd->RemoveArray(kModelFaceIdArrayName);
  cd->AddArray(entity);
  cd->AddArray(face);
  vtkNew<vtkStringArray> nameArray;
  nameArray->SetName(kPatchNamesArrayName);
  nameArray->SetNumberOfValues(maxId);
  vtkNew<vtkStringArray> typeArray;
  typeArray->SetName(kPatchTypesArrayName);
  typeArray->SetNumberOfValues(maxId);
  for (int id = 1; id <= maxId; ++id)
  {
    auto it = byId.find(id);
    nameArray->SetValue(id - 1, it == byId.end() ? "" : it->second->name);
    typeArray->SetValue(
      id - 1, PatchTypeName(it == byId.end() ? PatchType::Wall : it->second->type));
  }
  vtkFieldData* fd = surface->GetFieldData();
  fd->RemoveArray(kPatchNamesArrayName);
  fd->RemoveArray(kPatchTypesArrayName);
  fd->AddArray(nameArray);
  fd->AddArray(typeArray);
}

} // namespace bender
