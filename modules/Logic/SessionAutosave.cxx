#include "SessionAutosave.h"

#include "AtomicFile.h"
#include "InputValidation.h"
#include "WarpPlanIO.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>
#include <utility>
#include <vector>

namespace bender
{

namespace
{
using Json = nlohmann::ordered_json;

std::string Name(const std::string& path)
{
  return std::filesystem::path(path).filename().string();
}

// ---- Writing ----

// Every number written must be finite: JSON has no infinity, and a NaN read back as null
// would turn a recovered parameter into a different one.
double Finite(double value, const std::string& field)
{
  if (!std::isfinite(value))
  {
    throw SessionFileError(field + ": not a finite number");
  }
  return value;
}

Json Triple(const Vec3& v, const std::string& field)
{
  return Json::array({ Finite(v.x, field), Finite(v.y, field), Finite(v.z, field) });
}

Json Triple(const std::array<double, 3>& v, const std::string& field)
{
  return Json::array({ Finite(v[0], field), Finite(v[1], field), Finite(v[2], field) });
}

Json Points(const std::vector<Point3>& points, const std::string& field)
{
  Json list = Json::array();
  for (const Point3& p : points)
  {
    list.push_back(Triple(p, field));
  }
  return list;
}

Json VolumeToJson(const SessionVolume& volume)
{
  Json v;
  v["path"] = volume.path;
  v["name"] = volume.name;
  if (!volume.dicomSeriesUid.empty())
  {
    v["series"] = volume.dicomSeriesUid;
  }
  const ImageGeometry& g = volume.geometry;
  v["size"] = Json::array({ g.size[0], g.size[1], g.size[2] });
  v["spacing"] = Triple(g.spacing, "volume.spacing");
  v["origin"] = Triple(g.origin, "volume.origin");
  Json direction = Json::array();
  for (double d : g.direction)
  {
    direction.push_back(Finite(d, "volume.direction"));
  }
  v["direction"] = direction;
  if (!volume.maskPath.empty())
  {
    v["mask"] = volume.maskPath;
  }
  return v;
}

Json SegmentationToJson(const SegmentationSettings& settings)
{
  const SegmentationParameters& s = settings.segmentation;
  Json j;
  j["method"] = s.method == SegmentationMethod::Vesselness ? "vesselness" : "threshold";
  j["lower"] = Finite(s.lower, "segmentation.lower");
  j["upper"] = Finite(s.upper, "segmentation.upper");
  j["seeds"] = Points(s.seeds, "segmentation.seeds");
  j["fillHoles"] = s.fillHoles;
  j["closingRadius"] = Finite(s.closingRadius, "segmentation.closingRadius");
  j["minRadius"] = Finite(s.minRadius, "segmentation.minRadius");
  j["maxRadius"] = Finite(s.maxRadius, "segmentation.maxRadius");
  j["scales"] = s.scales;
  j["alpha"] = Finite(s.alpha, "segmentation.alpha");
  j["beta"] = Finite(s.beta, "segmentation.beta");
  j["gamma"] = Finite(s.gamma, "segmentation.gamma");
  j["vesselnessThreshold"] = Finite(s.vesselnessThreshold, "segmentation.vesselnessThreshold");
  j["brightVessels"] = s.brightVessels;
  j["levelSetIterations"] = s.levelSetIterations;
  j["levelSetSigma"] = Finite(s.levelSetSigma, "segmentation.levelSetSigma");
  j["levelSetPropagation"] = Finite(s.levelSetPropagation, "segmentation.levelSetPropagation");
  j["levelSetCurvature"] = Finite(s.levelSetCurvature, "segmentation.levelSetCurvature");
  const SurfaceParameters& f = settings.surface;
  j["extractor"] = f.extractor == SurfaceExtractor::Itk ? "itk" : "vtk";
  j["smoothing"] = Finite(f.smoothing, "segmentation.smoothing");
  j["targetTriangles"] = f.targetTriangles;
  j["surfaceSeeds"] = Points(f.seeds, "segmentation.surfaceSeeds");
  return j;
}

Json EndToJson(const RibbonEnd& end, const std::string& field)
{
  Json e;
  e["position"] = Triple(end.position, field + ".position");
  e["tangent"] = Triple(end.tangent, field + ".tangent");
  e["normal"] = Triple(end.normal, field + ".normal");
  return e;
}

Json RibbonToJson(const SessionRibbon& ribbon)
{
  Json r;
  r["start"] = EndToJson(ribbon.ribbon.start, "ribbon.start");
  r["end"] = EndToJson(ribbon.ribbon.end, "ribbon.end");
  r["extraTurns"] = ribbon.ribbon.extraTurns;
  r["radius"] = Finite(ribbon.radius, "ribbon.radius");
  r["decay"] = ribbon.decay.shape == DecayShape::Plateau ? "plateau" : "bell";
  r["plateau"] = Finite(ribbon.decay.plateau, "ribbon.plateau");
  r["vesselRadius"] = Finite(ribbon.vesselRadius, "ribbon.vesselRadius");
  return r;
}

// ---- Reading: every accessor names the file and the field it refuses ----

class Reader
{
public:
  explicit Reader(std::string file)
    : File(std::move(file))
  {
  }

  [[noreturn]] void Fail(const std::string& field, const std::string& problem) const
  {
    throw SessionFileError(this->File + ": " + field + ": " + problem);
  }

  const Json& Member(const Json& object, const char* key, const std::string& field) const
  {
    if (!object.contains(key))
    {
      this->Fail(field + "." + key, "missing");
    }
    return object[key];
  }

  double Number(const Json& object, const char* key, const std::string& field) const
  {
    const Json& value = this->Member(object, key, field);
    if (!value.is_number() || !std::isfinite(value.get<double>()))
    {
      this->Fail(field + "." + key, "not a finite number");
    }
    return value.get<double>();
  }

  long long Integer(const Json& object, const char* key, const std::string& field) const
  {
    const Json& value = this->Member(object, key, field);
    if (!value.is_number_integer())
    {
      this->Fail(field + "." + key, "not an integer");
    }
    return value.get<long long>();
  }

  bool Boolean(const Json& object, const char* key, const std::string& field) const
  {
    const Json& value = this->Member(object, key, field);
    if (!value.is_boolean())
    {
      this->Fail(field + "." + key, "not true or false");
    }
    return value.get<bool>();
  }

  std::string String(const Json& object, const char* key, const std::string& field) const
  {
    const Json& value = this->Member(object, key, field);
    if (!value.is_string())
    {
      this->Fail(field + "." + key, "not a string");
    }
    return value.get<std::string>();
  }

  std::array<double, 3> Triple(const Json& value, const std::string& field) const
  {
    if (!value.is_array() || value.size() != 3)
    {
      this->Fail(field, "not 3 numbers");
    }
    std::array<double, 3> v{};
    for (std::size_t i = 0; i < 3; ++i)
    {
      if (!value[i].is_number() || !std::isfinite(value[i].get<double>()))
      {
        this->Fail(field, "not 3 finite numbers");
      }
      v[i] = value[i].get<double>();
    }
    return v;
  }

  Vec3 Vector(const Json& object, const char* key, const std::string& field) const
  {
    const std::array<double, 3> v =
      this->Triple(this->Member(object, key, field), field + "." + key);
    return { v[0], v[1], v[2] };
  }

  std::vector<Point3> Points(const Json& object, const char* key, const std::string& field) const
  {
    const Json& list = this->Member(object, key, field);
    if (!list.is_array())
    {
      this->Fail(field + "." + key, "not a list of points");
    }
    std::vector<Point3> points;
    for (const Json& p : list)
    {
      points.push_back(this->Triple(p, field + "." + key));
    }
    return points;
  }

  SessionVolume Volume(const Json& v) const
  {
    const std::string field = "volume";
    if (!v.is_object())
    {
      this->Fail(field, "not an object");
    }
    SessionVolume volume;
    volume.path = this->String(v, "path", field);
    if (volume.path.empty())
    {
      this->Fail(field + ".path", "empty");
    }
    volume.name = this->String(v, "name", field);
    if (v.contains("series"))
    {
      volume.dicomSeriesUid = this->String(v, "series", field);
    }
    const Json& size = this->Member(v, "size", field);
    if (!size.is_array() || size.size() != 3)
    {
      this->Fail(field + ".size", "not 3 positive integers");
    }
    for (std::size_t i = 0; i < 3; ++i)
    {
      if (!size[i].is_number_integer() || size[i].get<long long>() <= 0)
      {
        this->Fail(field + ".size", "not 3 positive integers");
      }
      volume.geometry.size[i] = size[i].get<std::size_t>();
    }
    volume.geometry.spacing = this->Triple(this->Member(v, "spacing", field), field + ".spacing");
    if (std::any_of(volume.geometry.spacing.begin(),
          volume.geometry.spacing.end(),
          [](double s) { return !(s > 0.0); }))
    {
      this->Fail(field + ".spacing", "not 3 positive numbers");
    }
    volume.geometry.origin = this->Triple(this->Member(v, "origin", field), field + ".origin");
    const Json& direction = this->Member(v, "direction", field);
    if (!direction.is_array() || direction.size() != 9)
    {
      this->Fail(field + ".direction", "not 9 numbers");
    }
    for (std::size_t i = 0; i < 9; ++i)
    {
      if (!direction[i].is_number() || !std::isfinite(direction[i].get<double>()))
      {
        this->Fail(field + ".direction", "not 9 finite numbers");
      }
      volume.geometry.direction[i] = direction[i].get<double>();
    }
    if (v.contains("mask"))
    {
      volume.maskPath = this->String(v, "mask", field);
    }
    return volume;
  }

  SegmentationSettings Segmentation(const Json& j) const
  {
    const std::string field = "segmentation";
    if (!j.is_object())
    {
      this->Fail(field, "not an object");
    }
    SegmentationSettings settings;
    SegmentationParameters& s = settings.segmentation;
    const std::string method = this->String(j, "method", field);
    if (method != "threshold" && method != "vesselness")
    {
      this->Fail(field + ".method", "'" + method + "' is not threshold or vesselness");
    }
    s.method =
      method == "vesselness" ? SegmentationMethod::Vesselness : SegmentationMethod::Threshold;
    s.lower = this->Number(j, "lower", field);
    s.upper = this->Number(j, "upper", field);
    s.seeds = this->Points(j, "seeds", field);
    s.fillHoles = this->Boolean(j, "fillHoles", field);
    s.closingRadius = this->Number(j, "closingRadius", field);
    s.minRadius = this->Number(j, "minRadius", field);
    s.maxRadius = this->Number(j, "maxRadius", field);
    s.scales = static_cast<int>(std::clamp<long long>(this->Integer(j, "scales", field),
      std::numeric_limits<int>::min(),
      std::numeric_limits<int>::max()));
    s.alpha = this->Number(j, "alpha", field);
    s.beta = this->Number(j, "beta", field);
    s.gamma = this->Number(j, "gamma", field);
    s.vesselnessThreshold = this->Number(j, "vesselnessThreshold", field);
    s.brightVessels = this->Boolean(j, "brightVessels", field);
    s.levelSetIterations =
      static_cast<int>(std::clamp<long long>(this->Integer(j, "levelSetIterations", field),
        std::numeric_limits<int>::min(),
        std::numeric_limits<int>::max()));
    s.levelSetSigma = this->Number(j, "levelSetSigma", field);
    s.levelSetPropagation = this->Number(j, "levelSetPropagation", field);
    s.levelSetCurvature = this->Number(j, "levelSetCurvature", field);
    SurfaceParameters& f = settings.surface;
    const std::string extractor = this->String(j, "extractor", field);
    if (extractor != "vtk" && extractor != "itk")
    {
      this->Fail(field + ".extractor", "'" + extractor + "' is not vtk or itk");
    }
    f.extractor = extractor == "itk" ? SurfaceExtractor::Itk : SurfaceExtractor::Vtk;
    f.smoothing = this->Number(j, "smoothing", field);
    const long long target = this->Integer(j, "targetTriangles", field);
    if (target < 0)
    {
      this->Fail(field + ".targetTriangles", "negative");
    }
    f.targetTriangles = static_cast<std::size_t>(target);
    f.seeds = this->Points(j, "surfaceSeeds", field);
    // The ranges the Segment panel and the session accept.
    std::string problem;
    if (!CheckSegmentationSettings(settings, problem))
    {
      this->Fail(field, problem);
    }
    return settings;
  }

  RibbonEnd End(const Json& j, const char* key) const
  {
    const std::string field = std::string("ribbon.") + key;
    const Json& e = this->Member(j, key, "ribbon");
    if (!e.is_object())
    {
      this->Fail(field, "not an object");
    }
    RibbonEnd end;
    end.position = this->Vector(e, "position", field);
    end.tangent = this->Vector(e, "tangent", field);
    end.normal = this->Vector(e, "normal", field);
    return end;
  }

  SessionRibbon Ribbon(const Json& j) const
  {
    const std::string field = "ribbon";
    if (!j.is_object())
    {
      this->Fail(field, "not an object");
    }
    SessionRibbon ribbon;
    ribbon.ribbon.start = this->End(j, "start");
    ribbon.ribbon.end = this->End(j, "end");
    const long long turns = this->Integer(j, "extraTurns", field);
    if (turns < -1000 || turns > 1000)
    {
      this->Fail(field + ".extraTurns", "out of range [-1000, 1000]");
    }
    ribbon.ribbon.extraTurns = static_cast<int>(turns);
    ribbon.radius = this->Number(j, "radius", field);
    if (!(ribbon.radius > 0.0))
    {
      this->Fail(field + ".radius", "not positive");
    }
    const std::string decay = this->String(j, "decay", field);
    if (decay != "bell" && decay != "plateau")
    {
      this->Fail(field + ".decay", "'" + decay + "' is not bell or plateau");
    }
    ribbon.decay.shape = decay == "plateau" ? DecayShape::Plateau : DecayShape::Bell;
    ribbon.decay.plateau = this->Number(j, "plateau", field);
    if (ribbon.decay.plateau < 0.0 || ribbon.decay.plateau > 0.95)
    {
      this->Fail(field + ".plateau", "out of range [0, 0.95]");
    }
    ribbon.vesselRadius = this->Number(j, "vesselRadius", field);
    if (ribbon.vesselRadius < 0.0)
    {
      this->Fail(field + ".vesselRadius", "negative");
    }
    return ribbon;
  }

private:
  std::string File;
};

bool Near(double a, double b, double tolerance)
{
  return std::abs(a - b) <= tolerance * std::max({ 1.0, std::abs(a), std::abs(b) });
}
}

void WriteSessionFile(const SessionSnapshot& snapshot, const std::string& path)
{
  Json root;
  root["format"] = "bender-session";
  root["version"] = SessionFileVersion;
  root["source"] = snapshot.sourcePath;
  if (!snapshot.surfaceName.empty())
  {
    root["name"] = snapshot.surfaceName;
  }
  root["frame"] = snapshot.frame;
  try
  {
    root["plan"] = WarpPlanToJson(snapshot.plan, Name(path) + ": plan");
    if (snapshot.volume)
    {
      root["volume"] = VolumeToJson(*snapshot.volume);
    }
    if (snapshot.segmentation)
    {
      root["segmentation"] = SegmentationToJson(*snapshot.segmentation);
    }
    if (snapshot.ribbon)
    {
      root["ribbon"] = RibbonToJson(*snapshot.ribbon);
    }
  }
  catch (const WarpPlanError& e)
  {
    throw SessionFileError(e.what());
  }
  catch (const SessionFileError& e)
  {
    throw SessionFileError(Name(path) + ": " + e.what());
  }

  const std::filesystem::path target(path);
  std::error_code ec;
  if (target.has_parent_path())
  {
    std::filesystem::create_directories(target.parent_path(), ec);
  }
  // The project's atomic write: a unique temporary file, flushed to disk, then renamed, so a
  // crash or a second instance never leaves a truncated session file.
  const std::string text = root.dump(2) + "\n";
  std::string problem;
  const bool written = AtomicWriteText(path, text, problem);
  if (!written)
  {
    throw SessionFileError(Name(path) + ": " + problem);
  }
}

SessionSnapshot ReadSessionFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throw SessionFileError(Name(path) + ": cannot be opened for reading");
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  Json root;
  try
  {
    // Nesting deeper than any session needs is refused before it can exhaust the stack.
    root = Json::parse(buffer.str(),
      [](int depth, Json::parse_event_t, Json&)
      {
        if (depth > 128)
        {
          throw SessionFileError("JSON nested more than 128 levels deep");
        }
        return true;
      });
  }
  catch (const SessionFileError& e)
  {
    throw SessionFileError(Name(path) + ": " + e.what());
  }
  catch (const nlohmann::json::exception& e)
  {
    // nlohmann quotes the bytes it last read, which come from the file and may be anything.
    throw SessionFileError(
      Name(path) + ": not valid JSON (" + io_detail::CleanMessage(e.what(), 300) + ")");
  }
  // Every field is type-checked before it is read: nlohmann's value() throws on a wrong type.
  const auto format = root.is_object() ? root.find("format") : root.end();
  if (format == root.end() || !format->is_string() ||
    format->get<std::string>() != "bender-session")
  {
    throw SessionFileError(Name(path) + ": format: not a bender-session file");
  }
  if (!root.contains("version") || !root["version"].is_number_integer() ||
    root["version"].get<long long>() < 1 || root["version"].get<long long>() > SessionFileVersion)
  {
    throw SessionFileError(Name(path) +
      ": version: unknown session file version (this Bender "
      "reads 1 to " +
      std::to_string(SessionFileVersion) + ")");
  }
  if (!root.contains("source") || !root["source"].is_string())
  {
    throw SessionFileError(Name(path) + ": source: missing or not a string");
  }
  if (!root.contains("plan") || !root["plan"].is_object())
  {
    throw SessionFileError(Name(path) + ": plan: missing or not an object");
  }
  SessionSnapshot snapshot;
  snapshot.sourcePath = root["source"].get<std::string>();
  if (root.contains("frame") && !root["frame"].is_string())
  {
    throw SessionFileError(Name(path) + ": frame: not a string");
  }
  snapshot.frame = root.value("frame", std::string("LPS"));
  if (root.contains("name"))
  {
    if (!root["name"].is_string())
    {
      throw SessionFileError(Name(path) + ": name: not a string");
    }
    snapshot.surfaceName = root["name"].get<std::string>();
  }
  try
  {
    snapshot.plan = WarpPlanFromJson(root["plan"], Name(path) + ": plan");
  }
  catch (const WarpPlanError& e)
  {
    throw SessionFileError(e.what());
  }
  // Version 1 had none of these; a version 2 file may lack any of them.
  const Reader reader(Name(path));
  if (root.contains("volume"))
  {
    snapshot.volume = reader.Volume(root["volume"]);
  }
  if (root.contains("segmentation"))
  {
    snapshot.segmentation = reader.Segmentation(root["segmentation"]);
  }
  if (root.contains("ribbon"))
  {
    snapshot.ribbon = reader.Ribbon(root["ribbon"]);
  }
  return snapshot;
}

bool SameVolumeGeometry(const ImageGeometry& a, const ImageGeometry& b)
{
  constexpr double tolerance = 1e-6;
  for (std::size_t i = 0; i < 3; ++i)
  {
    if (a.size[i] != b.size[i] || !Near(a.spacing[i], b.spacing[i], tolerance) ||
      !Near(a.origin[i], b.origin[i], tolerance))
    {
      return false;
    }
  }
  for (std::size_t i = 0; i < 9; ++i)
  {
    if (std::abs(a.direction[i] - b.direction[i]) > tolerance)
    {
      return false;
    }
  }
  return true;
}

std::string DescribeVolumeGeometry(const ImageGeometry& g)
{
  std::ostringstream text;
  text << g.size[0] << "x" << g.size[1] << "x" << g.size[2] << " voxels of " << g.spacing[0] << "x"
       << g.spacing[1] << "x" << g.spacing[2] << " mm at (" << g.origin[0] << ", " << g.origin[1]
       << ", " << g.origin[2] << ")";
  return text.str();
}

AutosaveCopies::AutosaveCopies(std::function<void()> finished)
  : Finished(std::move(finished))
{
}

AutosaveCopies::~AutosaveCopies()
{
  this->Wait();
}

std::string AutosaveCopies::CopyOf(const std::shared_ptr<const void>& object,
  const std::string& path,
  const WriteFunction& write,
  std::string& problem)
{
  problem.clear();
  if (!object || path.empty())
  {
    return {};
  }
  std::lock_guard<std::mutex> lock(this->Mutex);
  Slot& slot = this->Slots[path];
  if (slot.written.lock() == object)
  {
    return path;
  }
  if (slot.writing)
  {
    return {}; // its end calls Finished, and the next autosave asks again
  }
  if (slot.failed.lock() == object)
  {
    problem = std::move(slot.problem);
    slot.problem.clear();
    return {};
  }
  if (slot.thread.joinable())
  {
    // The last write has ended (writing is reset last thing under the lock): this only reaps
    // the thread, which may still be in Finished, which never takes the lock.
    slot.thread.join();
  }
  // The file at `path` is about to hold another object.
  slot.written.reset();
  slot.failed.reset();
  slot.problem.clear();
  slot.writing = object;
  slot.thread = std::thread(&AutosaveCopies::Run, this, &slot, path, object, write);
  return {};
}

void AutosaveCopies::Run(Slot* slot,
  std::string path,
  std::shared_ptr<const void> object,
  WriteFunction write)
{
  std::string error;
  try
  {
    write(path);
  }
  catch (const std::exception& e) // the writers' errors, ITK's and std's: end of the thread
  {
    error = e.what();
  }
  catch (...)
  {
    error = path + ": unknown error";
  }
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (error.empty())
    {
      slot->written = object;
    }
    else
    {
      slot->failed = object;
      slot->problem = error;
    }
    slot->writing.reset();
  }
  object.reset();
  if (this->Finished)
  {
    this->Finished();
  }
}

bool AutosaveCopies::IsWriting() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return std::any_of(this->Slots.begin(),
    this->Slots.end(),
    [](const auto& entry) { return static_cast<bool>(entry.second.writing); });
}

void AutosaveCopies::Wait()
{
  std::vector<std::thread> threads;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    for (auto& entry : this->Slots)
    {
      if (entry.second.thread.joinable())
      {
        threads.push_back(std::move(entry.second.thread));
      }
    }
  }
  for (std::thread& thread : threads)
  {
    thread.join();
  }
}

void AutosaveCopies::Forget()
{
  this->Wait();
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Slots.clear();
}

std::string SessionVolumeCopyPath(const std::string& sessionPath)
{
  return sessionPath + ".volume.nrrd";
}

std::string SessionMaskCopyPath(const std::string& sessionPath)
{
  return sessionPath + ".mask.nrrd";
}

void RemoveSessionSideFiles(const std::string& sessionPath)
{
  if (sessionPath.empty())
  {
    return;
  }
  std::error_code ec;
  std::filesystem::remove(SessionVolumeCopyPath(sessionPath), ec);
  std::filesystem::remove(SessionMaskCopyPath(sessionPath), ec);
}

} // namespace bender
