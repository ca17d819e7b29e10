#include "CfdCaseFile.h"

#include "AtomicFile.h"
#include "BenderErrors.h"

#include <fstream>
#include <sstream>

namespace bender
{

nlohmann::ordered_json CfdPatchesJson(const std::vector<CfdPatch>& patches)
{
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const CfdPatch& p : patches)
  {
    nlohmann::ordered_json j;
    j["name"] = p.name;
    j["type"] = PatchTypeName(p.type);
    j["triangles"] = p.triangles;
    j["area"] = p.area;
    j["diameter"] = p.diameter;
    j["centre"] = p.centre;
    j["normal"] = p.normal;
    list.push_back(j);
  }
  return list;
}

std::string CfdFoamFile(const std::filesystem::path& caseDirectory)
{
  const std::filesystem::path path = caseDirectory / "bender.foam";
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
  {
    std::string problem;
    if (!AtomicWriteText(path.string(), "", problem))
    {
      throw Error(path.string() + ": " + problem);
    }
  }
  return path.string();
}

std::string ReadTextFile(const std::filesystem::path& path)
{
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

} // namespace bender
