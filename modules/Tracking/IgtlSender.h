#ifndef bender_IgtlSender_h
#define bender_IgtlSender_h

#include "IgtlSocket.h"
#include "Quaternion.h"
#include "Vec3.h"
#include "WarpPlan.h"

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace bender
{

/// A surface to send, in Bender's LPS millimetres (plain types, so that this module needs no
/// VTK; the application fills it from its vtkPolyData: points and the polygons' point ids).
struct IgtlSurface
{
  std::vector<Vec3> points;
  std::vector<std::vector<std::uint32_t>> polygons;
};

/// The bytes of a POLYDATA message (header version 1) carrying `surface` in RAS millimetres
/// (x and y negated), packed by the OpenIGTLink library (igtl::PolyDataMessage). Throws
/// TrackingConfigurationError naming `name` when a polygon refers to a missing point, has
/// fewer than 3 points, or a point is not finite.
std::vector<std::uint8_t> EncodeIgtlPolyData(const IgtlSurface& surface, const std::string& name);

/// The bytes of a TRANSFORM message (packed by igtl::TransformMessage) for a frame given in
/// LPS (position in mm, orientation maps the frame's axes to LPS); sent in RAS.
std::vector<std::uint8_t> EncodeIgtlTransformMessage(const std::string& name,
  const Vec3& positionLps,
  const Quaternion& orientationLps);

/// The frame of a ribbon end as a rotation: x = tangent, z = normal (made orthogonal to the
/// tangent), y = z cross x. Throws TrackingConfigurationError when the tangent is zero or the
/// normal is parallel to it.
Quaternion IgtlRibbonEndFrame(const RibbonEnd& end);

/// Sends surfaces and frames to an OpenIGTLink server (3D Slicer's OpenIGTLinkIF connector in
/// server mode, or any peer that listens). Every call is synchronous with a bounded write
/// time; SendSurfaceIfDue() limits the rate during a bend. Errors throw TrackingError
/// subclasses with one line naming the peer (DeviceNotFoundError when nobody listens,
/// DeviceDisconnectedError when the peer went away: Connect() again).
class IgtlSender
{
public:
  struct Options
  {
    std::string host = "127.0.0.1";
    int port = 18944;
    std::chrono::milliseconds connectTimeout{ 3000 };
    std::chrono::milliseconds writeTimeout{ 2000 };
    double maxSurfaceRateHz = 10.0; ///< SendSurfaceIfDue: at most this many surfaces a second
  };

  explicit IgtlSender(Options options);

  void Connect();
  bool IsConnected() const { return this->Link.IsOpen(); }
  void Close() { this->Link.Close(); }

  void SendSurface(const IgtlSurface& surface, const std::string& name);
  /// Sends only when 1/maxSurfaceRateHz has passed since the last surface sent; returns
  /// whether it sent. The caller keeps the newest surface and calls again (a bend that stops
  /// should end with SendSurface so that the final shape is never skipped).
  bool SendSurfaceIfDue(const IgtlSurface& surface, const std::string& name);
  void SendTransform(const std::string& name,
    const Vec3& positionLps,
    const Quaternion& orientationLps);
  /// Sends the ribbon's two end frames as TRANSFORMs named `prefix` + "Start" and `prefix` +
  /// "End" (see IgtlRibbonEndFrame); `prefix` has at most 15 characters.
  void SendRibbonEnds(const RibbonSpec& ribbon, const std::string& prefix = "Ribbon");

  std::uint64_t MessagesSent() const { return this->Messages; }
  std::uint64_t BytesSent() const { return this->Bytes; }
  const Options& GetOptions() const { return this->Opts; }

private:
  void Send(const std::vector<std::uint8_t>& bytes);

  Options Opts;
  IgtlConnection Link;
  std::chrono::steady_clock::time_point LastSurface{};
  bool SentSurface = false;
  std::uint64_t Messages = 0;
  std::uint64_t Bytes = 0;
};

} // namespace bender

#endif
