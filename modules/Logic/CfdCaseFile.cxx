#include "CfdCaseFile.h"

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

std::string ReadTextFile(const std::filesystem::path& path)
{
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

} // namespace bender
