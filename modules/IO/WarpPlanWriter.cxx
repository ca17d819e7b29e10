#include "WarpPlanIO.h"

#include "FileUtilities.h"
#include "InputValidation.h"
#include "StringUtil.h"
#include "WarpPlanFormat.h"

#include <charconv>
#include <cmath>

// Writing a plan (warp-file-format.md): the JSON object of a plan and the file's layout. The
// reader is WarpPlanIO.cxx.

namespace bender
{

std::string plan_format::ParseErrorText(const std::string& what)
{
  const std::size_t tag = what.find("] ");
  return io_detail::CleanMessage(tag == std::string::npos ? what : what.substr(tag + 2), 300);
}

namespace
{

using json = plan_format::json;
using namespace plan_format;

// Shortest text that reads back as the same double (locale-independent).
std::string NumberText(double value)
{
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  std::string text(buffer, result.ptr);
  // "-0" would read back as the integer 0 and lose the sign.
  if (text == "-0")
  {
    text = "-0.0";
  }
  return text;
}

// Builds the JSON object of a plan; every failure names the JSON path of the field.
class PlanBuilder
{
public:
  explicit PlanBuilder(std::string source)
    : Source(std::move(source))
  {
  }

  json Build(const WarpPlan& plan) const
  {
    json document;
    document["format"] = FormatName;
    document["version"] = plan.cfdSteps.empty() ? KnownVersion : CfdStepVersion;
    document["units"] = plan.units;
    document["warps"] = json::array();
    for (std::size_t i = 0; i < plan.warps.size(); ++i)
    {
      document["warps"].push_back(this->Warp(plan.warps[i], "warps[" + std::to_string(i) + "]"));
    }
    if (!plan.cfdSteps.empty())
    {
      json& steps = document[CfdStepsKey] = json::array();
      for (std::size_t i = 0; i < plan.cfdSteps.size(); ++i)
      {
        steps.push_back(
          this->Step(plan.cfdSteps[i], std::string(CfdStepsKey) + "[" + std::to_string(i) + "]"));
      }
    }
    this->AddExtra(document, plan.extraFields, "");
    return document;
  }

private:
  std::string Source;

  [[noreturn]] void Fail(const std::string& path, const std::string& problem) const
  {
    throw WarpPlanError(this->Source + ": " + path + ": " + problem);
  }

  json Number(double value, const std::string& path) const
  {
    if (!std::isfinite(value))
    {
      this->Fail(path, "not a finite number (JSON cannot hold it)");
    }
    return value;
  }

  json Vector(const Vec3& v, const std::string& path) const
  {
    return json::array({ this->Number(v.x, path + "[0]"),
      this->Number(v.y, path + "[1]"),
      this->Number(v.z, path + "[2]") });
  }

  json End(const RibbonEnd& end, const std::string& path) const
  {
    json object;
    object["position"] = this->Vector(end.position, path + ".position");
    object["tangent"] = this->Vector(end.tangent, path + ".tangent");
    object["normal"] = this->Vector(end.normal, path + ".normal");
    return object;
  }

  json Ribbon(const RibbonSpec& ribbon, const std::string& path) const
  {
    json object;
    object["start"] = this->End(ribbon.start, path + ".start");
    object["end"] = this->End(ribbon.end, path + ".end");
    object["extraTurns"] = ribbon.extraTurns;
    return object;
  }

  json Warp(const WarpSpec& warp, const std::string& path) const
  {
    json object;
    object["initial"] = this->Ribbon(warp.initial, path + ".initial");
    object["final"] = this->Ribbon(warp.final, path + ".final");
    object["radius"] = this->Number(warp.radius, path + ".radius");
    json decay;
    decay["shape"] = warp.decay.shape == DecayShape::Plateau ? "plateau" : "bell";
    decay["plateau"] = this->Number(warp.decay.plateau, path + ".decay.plateau");
    object["decay"] = decay;
    object["reverseScrews"] = warp.reverseScrews;
    if (warp.subdivision)
    {
      json subdivision;
      subdivision["tolerance"] =
        this->Number(warp.subdivision->tolerance, path + ".subdivision.tolerance");
      subdivision["maxPasses"] = warp.subdivision->maxPasses;
      object["subdivision"] = subdivision;
    }
    this->AddExtra(object, warp.extraFields, path + ".");
    return object;
  }

  json Step(const CfdStep& step, const std::string& path) const
  {
    json object;
    object["afterWarps"] = step.afterWarps;
    object["clip"] = step.clip;
    object["cap"] = step.cap;
    object["inletExtension"] = this->Number(step.inletExtension, path + ".inletExtension");
    object["outletExtension"] = this->Number(step.outletExtension, path + ".outletExtension");
    object["ends"] = json::array();
    for (std::size_t i = 0; i < step.ends.size(); ++i)
    {
      const std::string at = path + ".ends[" + std::to_string(i) + "]";
      json end;
      end["position"] = this->Vector(step.ends[i].position, at + ".position");
      if (step.ends[i].distance >= 0.0)
      {
        end["distance"] = this->Number(step.ends[i].distance, at + ".distance");
      }
      object["ends"].push_back(end);
    }
    object["names"] = json::array();
    for (std::size_t i = 0; i < step.names.size(); ++i)
    {
      const std::string at = path + ".names[" + std::to_string(i) + "]";
      json name;
      name["position"] = this->Vector(step.names[i].position, at + ".position");
      name["name"] = step.names[i].name;
      name["inlet"] = step.names[i].inlet;
      object["names"].push_back(name);
    }
    object["extensionFactors"] = json::array();
    for (std::size_t i = 0; i < step.extensionFactors.size(); ++i)
    {
      const std::string at = path + ".extensionFactors[" + std::to_string(i) + "]";
      json factor;
      factor["position"] = this->Vector(step.extensionFactors[i].position, at + ".position");
      factor["factor"] = this->Number(step.extensionFactors[i].factor, at + ".factor");
      object["extensionFactors"].push_back(factor);
    }
    this->AddExtra(object, step.extraFields, path + ".");
    return object;
  }

  // Unknown fields kept as JSON text by the parser go back after the known ones.
  void AddExtra(json& object,
    const std::map<std::string, std::string>& extra,
    const std::string& prefix) const
  {
    for (const auto& [key, text] : extra)
    {
      if (object.contains(key) || key == "subdivision")
      {
        this->Fail(prefix + key, "an extra field may not have the name of a known field");
      }
      try
      {
        object[key] = json::parse(text);
      }
      catch (const json::parse_error& e)
      {
        this->Fail(
          prefix + key, "extra field is not valid JSON (" + ParseErrorText(e.what()) + ")");
      }
    }
  }
};

// True for a value that is printed on one line: a scalar, or an array or object none of
// whose members is an object (ribbon ends, decay, vectors).
bool Flat(const json& value)
{
  if (!value.is_structured())
  {
    return true;
  }
  for (const json& member : value)
  {
    if (member.is_object() || (member.is_array() && !Flat(member)))
    {
      return false;
    }
  }
  return true;
}

// The plan file's layout: one member per line, short objects and vectors on one line,
// numbers as the shortest text that reads back as the same double.
void Print(const json& value, const std::string& indent, std::string& out)
{
  if (value.is_number_float())
  {
    out += NumberText(value.get<double>());
    return;
  }
  if (!value.is_structured())
  {
    out += value.dump();
    return;
  }
  const bool object = value.is_object();
  if (value.empty())
  {
    out += object ? "{}" : "[]";
    return;
  }
  const bool flat = Flat(value);
  out += object ? (flat ? "{ " : "{\n") : (flat ? "[" : "[\n");
  const std::string inner = indent + "  ";
  bool first = true;
  for (auto it = value.begin(); it != value.end(); ++it)
  {
    if (!first)
    {
      out += flat ? ", " : ",\n";
    }
    first = false;
    if (!flat)
    {
      out += inner;
    }
    if (object)
    {
      out += json(it.key()).dump() + ": ";
    }
    Print(*it, inner, out);
  }
  if (flat)
  {
    out += object ? " }" : "]";
  }
  else
  {
    out += "\n" + indent + (object ? "}" : "]");
  }
}

} // namespace

nlohmann::ordered_json WarpPlanToJson(const WarpPlan& plan, const std::string& sourceName)
{
  return PlanBuilder(sourceName.empty() ? "plan" : sourceName).Build(plan);
}

std::string SerializeWarpPlan(const WarpPlan& plan)
{
  std::string text;
  Print(WarpPlanToJson(plan), "", text);
  return text + "\n";
}

void WriteWarpPlan(const WarpPlan& plan, const std::string& path)
{
  const std::string name = DisplayName(path);
  std::string text;
  Print(WarpPlanToJson(plan, name), "", text);
  text += "\n";
  std::string problem;
  const bool ok = AtomicWriteText(path, text, problem);
  if (!ok)
  {
    throw WarpPlanError(name + ": " + problem);
  }
}

} // namespace bender
