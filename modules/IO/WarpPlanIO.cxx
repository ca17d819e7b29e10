#include "WarpPlanIO.h"

#include "FileUtilities.h"
#include "GeometryErrors.h"
#include "InputValidation.h"
#include "RibbonWarp.h"
#include "StringUtil.h"

#include <nlohmann/json.hpp>

#include <charconv>
#include <climits>
#include <cmath>
#include <fstream>
#include <iterator>
#include <set>

namespace bender
{

namespace
{

// Ordered: unknown fields are written back with their members in the order they were read.
using json = nlohmann::ordered_json;

constexpr const char* FormatName = "bender-warps";
constexpr int KnownVersion = 1;
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
    if (!version.is_number_integer() || version.get<long long>() != KnownVersion)
    {
      this->Fail("version",
        "unsupported version " + version.dump() + " (this reader knows version " +
          std::to_string(KnownVersion) + ")");
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
    const json& warps = this->Required(document, "warps", "");
    if (!warps.is_array())
    {
      this->Fail("warps", "expected an array, found " + Describe(warps));
    }
    for (std::size_t i = 0; i < warps.size(); ++i)
    {
      plan.warps.push_back(this->ParseWarp(warps[i], "warps[" + std::to_string(i) + "]"));
    }
    static const std::set<std::string> known{ "format", "version", "units", "warps" };
    for (const auto& [key, value] : document.items())
    {
      if (!known.count(key))
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
      if (!reverse->is_boolean())
      {
        this->Fail(
          Join(path, "reverseScrews"), "expected true or false, found " + Describe(*reverse));
      }
      warp.reverseScrews = reverse->get<bool>();
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
};

// "[json.exception.parse_error.101] parse error at line 3, column 7: ..." without the tag, as
// one printable line: nlohmann quotes the bytes it last read ("last read: '...'"), which come
// from the file and may be anything (found by fuzz/fuzz_plan).
std::string ParseErrorText(const std::string& what)
{
  const std::size_t tag = what.find("] ");
  return io_detail::CleanMessage(tag == std::string::npos ? what : what.substr(tag + 2), 300);
}

struct TooDeep
{
};

// ---------------------------------------------------------------------------------------
// Writing

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
    document["version"] = KnownVersion;
    document["units"] = plan.units;
    document["warps"] = json::array();
    for (std::size_t i = 0; i < plan.warps.size(); ++i)
    {
      document["warps"].push_back(this->Warp(plan.warps[i], "warps[" + std::to_string(i) + "]"));
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

nlohmann::ordered_json WarpPlanToJson(const WarpPlan& plan, const std::string& sourceName)
{
  return PlanBuilder(sourceName.empty() ? "plan" : sourceName).Build(plan);
}

WarpPlan WarpPlanFromJson(const nlohmann::ordered_json& document, const std::string& sourceName)
{
  return ParseAndValidate(document, sourceName.empty() ? "plan" : sourceName);
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
