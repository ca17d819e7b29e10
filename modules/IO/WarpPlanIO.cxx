#include "WarpPlanIO.h"

#include "FileUtilities.h"
#include "GeometryErrors.h"
#include "InputValidation.h"
#include "PatchLabels.h"
#include "RibbonWarp.h"
#include "StringUtil.h"
#include "WarpPlanFormat.h"

#include <nlohmann/json.hpp>

#include <climits>
#include <cmath>
#include <fstream>
#include <iterator>
#include <set>

namespace bender
{

namespace
{

using json = plan_format::json;
using namespace plan_format;

// Deeper nesting than any plan needs; refused before it can exhaust the stack anywhere.
constexpr int MaxDepth = 64;
// A plan of thousands of warps is a few MiB; anything near this is not a plan.
constexpr std::uintmax_t MaxFileSize = 256u << 20;

// A JSON string as quoted in a message: ASCII only (DEL and non-ASCII escaped as \uXXXX, so the
// message stays one printable line) and at most 40 characters.
std::string Quoted(const json& value)
{
  const std::string text = value.dump(-1, ' ', true, json::error_handler_t::replace);
  return text.size() > 40 ? text.substr(0, 37) + "...\"" : text;
}

std::string Describe(const json& value)
{
  switch (value.type())
  {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return value.get<bool>() ? "true" : "false";
    case json::value_t::string:
      return "a string " + Quoted(value);
    case json::value_t::array:
      return "an array";
    case json::value_t::object:
      return "an object";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return value.dump();
    default:
      return "an unsupported value";
  }
}

// Structural parse of one document; every failure names the JSON path of the field.
class PlanParser
{
public:
  explicit PlanParser(std::string source)
    : Source(std::move(source))
  {
  }

  [[noreturn]] void Fail(const std::string& path, const std::string& problem) const
  {
    throw WarpPlanError(this->Source + ": " + (path.empty() ? "" : path + ": ") + problem);
  }

  WarpPlan Parse(const json& document) const
  {
    if (!document.is_object())
    {
      this->Fail("", "expected a JSON object at the top level, found " + Describe(document));
    }
    const json& format = this->Required(document, "format", "");
    if (!format.is_string())
    {
      this->Fail("format", "expected the string \"bender-warps\", found " + Describe(format));
    }
    if (format.get<std::string>() != FormatName)
    {
      this->Fail("format", "expected \"bender-warps\", found " + Quoted(format));
    }
    const json& version = this->Required(document, "version", "");
    if (!version.is_number())
    {
      this->Fail("version", "expected an integer, found " + Describe(version));
    }
    const long long number = version.is_number_integer() ? version.get<long long>() : 0;
    if (number != KnownVersion && number != CfdStepVersion)
    {
      this->Fail("version",
        "unsupported version " + version.dump() + " (this reader knows versions " +
          std::to_string(KnownVersion) + " and " + std::to_string(CfdStepVersion) + ")");
    }

    WarpPlan plan;
    if (const json* units = Optional(document, "units"))
    {
      if (!units->is_string())
      {
        this->Fail("units", "expected a string, found " + Describe(*units));
      }
      plan.units = units->get<std::string>();
    }
    const json& warps = this->Array(this->Required(document, "warps", ""), "warps");
    for (std::size_t i = 0; i < warps.size(); ++i)
    {
      plan.warps.push_back(this->ParseWarp(warps[i], "warps[" + std::to_string(i) + "]"));
    }
    // Version 1 knows no CFD step: there the field is an unknown one, kept as it is.
    const json* steps = number == CfdStepVersion ? Optional(document, CfdStepsKey) : nullptr;
    if (steps)
    {
      this->Array(*steps, CfdStepsKey);
      for (std::size_t i = 0; i < steps->size(); ++i)
      {
        const std::size_t earliest = plan.cfdSteps.empty() ? 0 : plan.cfdSteps.back().afterWarps;
        plan.cfdSteps.push_back(this->ParseCfdStep((*steps)[i],
          std::string(CfdStepsKey) + "[" + std::to_string(i) + "]",
          plan.warps.size(),
          earliest));
      }
    }
    static const std::set<std::string> known{ "format", "version", "units", "warps" };
    for (const auto& [key, value] : document.items())
    {
      if (!known.count(key) && !(steps && key == CfdStepsKey))
      {
        plan.extraFields[key] = value.dump();
      }
    }
    return plan;
  }

private:
  std::string Source;

  static std::string Join(const std::string& path, const std::string& key)
  {
    return path.empty() ? key : path + "." + key;
  }

  static const json* Optional(const json& object, const char* key)
  {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }

  const json& Required(const json& object, const char* key, const std::string& path) const
  {
    const json* value = Optional(object, key);
    if (!value)
    {
      this->Fail(Join(path, key), "missing");
    }
    return *value;
  }

  const json& Object(const json& value, const std::string& path) const
  {
    if (!value.is_object())
    {
      this->Fail(path, "expected an object, found " + Describe(value));
    }
    return value;
  }

  const json& Array(const json& value, const std::string& path) const
  {
    if (!value.is_array())
    {
      this->Fail(path, "expected an array, found " + Describe(value));
    }
    return value;
  }

  bool Boolean(const json& value, const std::string& path) const
  {
    if (!value.is_boolean())
    {
      this->Fail(path, "expected true or false, found " + Describe(value));
    }
    return value.get<bool>();
  }

  double Number(const json& value, const std::string& path) const
  {
    if (!value.is_number())
    {
      this->Fail(path, "expected a number, found " + Describe(value));
    }
    const double number = value.get<double>();
    if (!std::isfinite(number))
    {
      this->Fail(path, "not a finite number");
    }
    return number;
  }

  // A JSON integer (no fraction, no exponent) in [low, INT_MAX].
  int Integer(const json& value, const std::string& path, long long low) const
  {
    if (!value.is_number_integer())
    {
      this->Fail(path, "expected an integer, found " + Describe(value));
    }
    if (value.is_number_unsigned() ? value.get<unsigned long long>() > INT_MAX
                                   : value.get<long long>() > INT_MAX)
    {
      this->Fail(path, "out of range (found " + value.dump() + ")");
    }
    const long long number = value.get<long long>();
    if (number < low || number < INT_MIN)
    {
      this->Fail(path,
        (low == 0 ? std::string("must be >= 0") : std::string("out of range")) + " (found " +
          value.dump() + ")");
    }
    return static_cast<int>(number);
  }

  Vec3 Vector(const json& value, const std::string& path) const
  {
    if (!value.is_array() || value.size() != 3)
    {
      this->Fail(path,
        "expected an array of 3 numbers, found " +
          (value.is_array() ? "an array of " + std::to_string(value.size()) : Describe(value)));
    }
    Vec3 v;
    v.x = this->Number(value[0], path + "[0]");
    v.y = this->Number(value[1], path + "[1]");
    v.z = this->Number(value[2], path + "[2]");
    return v;
  }

  RibbonEnd ParseEnd(const json& value, const std::string& path) const
  {
    const json& object = this->Object(value, path);
    RibbonEnd end;
    end.position = this->Vector(this->Required(object, "position", path), Join(path, "position"));
    end.tangent = this->Vector(this->Required(object, "tangent", path), Join(path, "tangent"));
    end.normal = this->Vector(this->Required(object, "normal", path), Join(path, "normal"));
    const double t = Norm(end.tangent);
    if (!(t > 0.0))
    {
      this->Fail(Join(path, "tangent"), "zero vector");
    }
    if (!std::isfinite(t))
    {
      this->Fail(Join(path, "tangent"), "too large to normalise");
    }
    const double n = Norm(end.normal);
    if (!(n > 0.0))
    {
      this->Fail(Join(path, "normal"), "zero vector");
    }
    if (!std::isfinite(n))
    {
      this->Fail(Join(path, "normal"), "too large to normalise");
    }
    // warp-file-format.md: rejected when |N x T^| <= 1e-9 |N|.
    if (Norm(Cross(end.normal, end.tangent / t)) <= 1e-9 * n)
    {
      this->Fail(Join(path, "normal"), "parallel to the tangent");
    }
    return end;
  }

  RibbonSpec ParseRibbon(const json& value, const std::string& path) const
  {
    const json& object = this->Object(value, path);
    RibbonSpec ribbon;
    ribbon.start = this->ParseEnd(this->Required(object, "start", path), Join(path, "start"));
    ribbon.end = this->ParseEnd(this->Required(object, "end", path), Join(path, "end"));
    if (const json* turns = Optional(object, "extraTurns"))
    {
      ribbon.extraTurns = this->Integer(*turns, Join(path, "extraTurns"), INT_MIN);
    }
    return ribbon;
  }

  WarpSpec ParseWarp(const json& value, const std::string& path) const
  {
    const json& object = this->Object(value, path);
    WarpSpec warp;
    warp.initial =
      this->ParseRibbon(this->Required(object, "initial", path), Join(path, "initial"));
    warp.final = this->ParseRibbon(this->Required(object, "final", path), Join(path, "final"));
    warp.radius = this->Number(this->Required(object, "radius", path), Join(path, "radius"));
    if (!(warp.radius > 0.0))
    {
      this->Fail(Join(path, "radius"), "must be > 0 (found " + json(warp.radius).dump() + ")");
    }
    if (const json* decay = Optional(object, "decay"))
    {
      const std::string decayPath = Join(path, "decay");
      this->Object(*decay, decayPath);
      if (const json* shape = Optional(*decay, "shape"))
      {
        const std::string shapePath = Join(decayPath, "shape");
        if (!shape->is_string())
        {
          this->Fail(shapePath, "expected \"bell\" or \"plateau\", found " + Quoted(*shape));
        }
        const std::string name = shape->get<std::string>();
        if (name == "bell")
        {
          warp.decay.shape = DecayShape::Bell;
        }
        else if (name == "plateau")
        {
          warp.decay.shape = DecayShape::Plateau;
        }
        else
        {
          this->Fail(shapePath, "expected \"bell\" or \"plateau\", found " + Quoted(*shape));
        }
      }
      if (const json* plateau = Optional(*decay, "plateau"))
      {
        const std::string plateauPath = Join(decayPath, "plateau");
        warp.decay.plateau = this->Number(*plateau, plateauPath);
        // Checked with "bell" too: the value is kept and written back, so it must be valid.
        if (!(warp.decay.plateau >= 0.0 && warp.decay.plateau <= 0.95))
        {
          this->Fail(plateauPath, "must be in [0, 0.95] (found " + plateau->dump() + ")");
        }
      }
    }
    if (const json* reverse = Optional(object, "reverseScrews"))
    {
      warp.reverseScrews = this->Boolean(*reverse, Join(path, "reverseScrews"));
    }
    if (const json* subdivision = Optional(object, "subdivision"))
    {
      const std::string subPath = Join(path, "subdivision");
      this->Object(*subdivision, subPath);
      SubdivisionSpec spec;
      const std::string tolPath = Join(subPath, "tolerance");
      spec.tolerance = this->Number(this->Required(*subdivision, "tolerance", subPath), tolPath);
      if (!(spec.tolerance > 0.0))
      {
        this->Fail(tolPath, "must be > 0 (found " + json(spec.tolerance).dump() + ")");
      }
      if (const json* passes = Optional(*subdivision, "maxPasses"))
      {
        spec.maxPasses = this->Integer(*passes, Join(subPath, "maxPasses"), 0);
      }
      warp.subdivision = spec;
    }
    static const std::set<std::string> known{
      "initial", "final", "radius", "decay", "reverseScrews", "subdivision"
    };
    for (const auto& [key, member] : object.items())
    {
      if (!known.count(key))
      {
        warp.extraFields[key] = member.dump();
      }
    }
    return warp;
  }

  // A flow-extension factor, [0, 100].
  double Factor(const json& value, const std::string& path) const
  {
    const double factor = this->Number(value, path);
    if (!(factor >= 0.0 && factor <= 100.0))
    {
      this->Fail(path, "must be in [0, 100] (found " + value.dump() + ")");
    }
    return factor;
  }

  // The objects of the array `key` of `object` (none when absent), each read by `read`.
  template<typename Read>
  void Each(const json& object, const char* key, const std::string& path, Read read) const
  {
    if (const json* array = Optional(object, key))
    {
      const std::string arrayPath = Join(path, key);
      this->Array(*array, arrayPath);
      for (std::size_t i = 0; i < array->size(); ++i)
      {
        const std::string itemPath = arrayPath + "[" + std::to_string(i) + "]";
        read(this->Object((*array)[i], itemPath), itemPath);
      }
    }
  }

  CfdStep ParseCfdStep(const json& value,
    const std::string& path,
    std::size_t warps,
    std::size_t earliest) const
  {
    const json& object = this->Object(value, path);
    CfdStep step;
    const std::string afterPath = Join(path, "afterWarps");
    const json& after = this->Required(object, "afterWarps", path);
    step.afterWarps = static_cast<std::size_t>(this->Integer(after, afterPath, 0));
    if (step.afterWarps > warps)
    {
      this->Fail(
        afterPath, "the plan has " + std::to_string(warps) + " warps (found " + after.dump() + ")");
    }
    if (step.afterWarps < earliest)
    {
      this->Fail(afterPath,
        "the steps must be in the order applied (found " + after.dump() + " after " +
          std::to_string(earliest) + ")");
    }
    if (const json* clip = Optional(object, "clip"))
    {
      step.clip = this->Boolean(*clip, Join(path, "clip"));
    }
    if (const json* cap = Optional(object, "cap"))
    {
      step.cap = this->Boolean(*cap, Join(path, "cap"));
    }
    if (const json* inlet = Optional(object, "inletExtension"))
    {
      step.inletExtension = this->Factor(*inlet, Join(path, "inletExtension"));
    }
    if (const json* outlet = Optional(object, "outletExtension"))
    {
      step.outletExtension = this->Factor(*outlet, Join(path, "outletExtension"));
    }
    this->Each(object,
      "ends",
      path,
      [this, &step](const json& end, const std::string& at)
      {
        CfdStepEnd entry;
        entry.position = this->Vector(this->Required(end, "position", at), Join(at, "position"));
        if (const json* distance = Optional(end, "distance"))
        {
          entry.distance = this->Number(*distance, Join(at, "distance"));
          if (!(entry.distance >= 0.0))
          {
            this->Fail(Join(at, "distance"), "must be >= 0 (found " + distance->dump() + ")");
          }
        }
        step.ends.push_back(entry);
      });
    this->Each(object,
      "names",
      path,
      [this, &step](const json& name, const std::string& at)
      {
        CfdStepName entry;
        entry.position = this->Vector(this->Required(name, "position", at), Join(at, "position"));
        const json& text = this->Required(name, "name", at);
        if (!text.is_string() || !IsValidPatchName(text.get<std::string>()) ||
          text.get<std::string>() == "wall")
        {
          this->Fail(Join(at, "name"),
            "expected a patch name (letters, digits and '_', not starting with a digit, not "
            "\"wall\"), found " +
              Describe(text));
        }
        entry.name = text.get<std::string>();
        if (const json* inlet = Optional(name, "inlet"))
        {
          entry.inlet = this->Boolean(*inlet, Join(at, "inlet"));
        }
        step.names.push_back(entry);
      });
    this->Each(object,
      "extensionFactors",
      path,
      [this, &step](const json& factor, const std::string& at)
      {
        CfdStepFactor entry;
        entry.position = this->Vector(this->Required(factor, "position", at), Join(at, "position"));
        entry.factor = this->Factor(this->Required(factor, "factor", at), Join(at, "factor"));
        step.extensionFactors.push_back(entry);
      });
    static const std::set<std::string> known{ "afterWarps",
      "clip",
      "cap",
      "inletExtension",
      "outletExtension",
      "ends",
      "names",
      "extensionFactors" };
    for (const auto& [key, member] : object.items())
    {
      if (!known.count(key))
      {
        step.extraFields[key] = member.dump();
      }
    }
    return step;
  }
};

struct TooDeep
{
};

WarpPlan ParseAndValidate(const json& document, const std::string& source)
{
  const PlanParser parser(source);
  WarpPlan plan = parser.Parse(document);

  // Each warp must also be valid under the spec's convention 11; one bad warp rejects the
  // whole plan.
  for (std::size_t i = 0; i < plan.warps.size(); ++i)
  {
    const std::string path = "warps[" + std::to_string(i) + "]";
    try
    {
      RibbonWarp::Validate(plan.warps[i]);
    }
    catch (const GeometryError& e)
    {
      parser.Fail(e.field().empty() ? path : path + "." + e.field(), e.problem());
    }
  }
  return plan;
}

} // namespace

WarpPlan ParseWarpPlan(const std::string& jsonText, const std::string& sourceName)
{
  const std::string source = sourceName.empty() ? "plan" : sourceName;
  json document;
  try
  {
    document = json::parse(jsonText,
      [](int depth, json::parse_event_t, json&)
      {
        if (depth > MaxDepth)
        {
          throw TooDeep{};
        }
        return true;
      });
  }
  catch (const TooDeep&)
  {
    throw WarpPlanError(
      source + ": JSON nested more than " + std::to_string(MaxDepth) + " levels deep");
  }
  catch (const json::exception& e)
  {
    // parse_error (with its line and column), or out_of_range for a number such as 1e999.
    throw WarpPlanError(source + ": malformed JSON: " + ParseErrorText(e.what()));
  }

  return ParseAndValidate(document, source);
}

WarpPlan ReadWarpPlan(const std::string& path)
{
  const std::string name = DisplayName(path);
  std::uintmax_t size = 0;
  std::string problem;
  if (!io_detail::CheckReadableFile(path, size, problem))
  {
    throw WarpPlanError(name + ": " + problem);
  }
  if (size > MaxFileSize)
  {
    throw WarpPlanError(name + ": too large for a plan (" + std::to_string(size) + " bytes)");
  }
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad())
  {
    throw WarpPlanError(name + ": cannot read the file");
  }
  return ParseWarpPlan(text, name);
}

WarpPlan WarpPlanFromJson(const nlohmann::ordered_json& document, const std::string& sourceName)
{
  return ParseAndValidate(document, sourceName.empty() ? "plan" : sourceName);
}

} // namespace bender
