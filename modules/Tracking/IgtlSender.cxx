#include "IgtlSender.h"

#include "IgtlProtocol.h"
#include "TrackingErrors.h"

#include <igtlPolyDataMessage.h>
#include <igtlTransformMessage.h>

#include <cmath>
#include <cstring>

namespace bender
{

namespace
{
std::vector<std::uint8_t> PackedBytes(igtl::MessageBase* message)
{
  message->Pack();
  const auto* data = static_cast<const std::uint8_t*>(message->GetPackPointer());
  return std::vector<std::uint8_t>(data, data + message->GetPackSize());
}

void CheckName(const std::string& name)
{
  if (name.empty() || name.size() > 20)
  {
    throw TrackingConfigurationError(
      "igtl: device name '" + name + "' must have 1 to 20 characters");
  }
}
} // namespace

std::vector<std::uint8_t> EncodeIgtlPolyData(const IgtlSurface& surface, const std::string& name)
{
  CheckName(name);
  igtl::PolyDataPointArray::Pointer points = igtl::PolyDataPointArray::New();
  for (const Vec3& p : surface.points)
  {
    if (!IsFinite(p))
    {
      throw TrackingConfigurationError("igtl surface '" + name + "': a point is not finite");
    }
    const Vec3 ras = LpsToRas(p);
    points->AddPoint(float(ras.x), float(ras.y), float(ras.z));
  }
  igtl::PolyDataCellArray::Pointer polygons = igtl::PolyDataCellArray::New();
  for (std::size_t i = 0; i < surface.polygons.size(); ++i)
  {
    std::vector<igtlUint32> ids(surface.polygons[i].begin(), surface.polygons[i].end());
    if (ids.size() < 3)
    {
      throw TrackingConfigurationError(
        "igtl surface '" + name + "': polygon " + std::to_string(i) + " has fewer than 3 points");
    }
    for (igtlUint32 id : ids)
    {
      if (id >= surface.points.size())
      {
        throw TrackingConfigurationError("igtl surface '" + name + "': polygon " +
          std::to_string(i) + " refers to point " + std::to_string(id) + " of " +
          std::to_string(surface.points.size()));
      }
    }
    polygons->AddCell(int(ids.size()), ids.data());
  }
  igtl::PolyDataMessage::Pointer message = igtl::PolyDataMessage::New();
  message->SetDeviceName(name.c_str());
  message->SetPoints(points);
  message->SetPolygons(polygons);
  return PackedBytes(message);
}

std::vector<std::uint8_t> EncodeIgtlTransformMessage(const std::string& name,
  const Vec3& positionLps,
  const Quaternion& orientationLps)
{
  CheckName(name);
  if (!IsFinite(positionLps) || !std::isfinite(orientationLps.w) ||
    !std::isfinite(orientationLps.x) || !std::isfinite(orientationLps.y) ||
    !std::isfinite(orientationLps.z))
  {
    throw TrackingConfigurationError("igtl transform '" + name + "': not finite");
  }
  const Vec3 position = LpsToRas(positionLps);
  const Quaternion orientation = LpsToRas(orientationLps);
  igtl::Matrix4x4 m;
  igtl::IdentityMatrix(m);
  const Vec3 axes[3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  for (int c = 0; c < 3; ++c)
  {
    const Vec3 column = RotateByQuaternion(orientation, axes[c]);
    m[0][c] = float(column.x);
    m[1][c] = float(column.y);
    m[2][c] = float(column.z);
  }
  m[0][3] = float(position.x);
  m[1][3] = float(position.y);
  m[2][3] = float(position.z);
  igtl::TransformMessage::Pointer message = igtl::TransformMessage::New();
  message->SetDeviceName(name.c_str());
  message->SetMatrix(m);
  return PackedBytes(message);
}

Quaternion IgtlRibbonEndFrame(const RibbonEnd& end)
{
  const double tl = Norm(end.tangent);
  if (!(tl > 1e-12) || !IsFinite(end.tangent) || !IsFinite(end.normal))
  {
    throw TrackingConfigurationError("igtl: ribbon end has no tangent");
  }
  const Vec3 x = end.tangent * (1.0 / tl);
  const Vec3 n = end.normal - x * Dot(end.normal, x);
  const double nl = Norm(n);
  if (!(nl > 1e-9))
  {
    throw TrackingConfigurationError("igtl: ribbon end normal is parallel to its tangent");
  }
  const Vec3 z = n * (1.0 / nl);
  return QuaternionFromColumns(x, Cross(z, x), z);
}

IgtlSender::IgtlSender(Options options)
  : Opts(std::move(options))
{
  if (this->Opts.host.empty() || this->Opts.port < 1 || this->Opts.port > 65535 ||
    !(this->Opts.maxSurfaceRateHz > 0.0 && std::isfinite(this->Opts.maxSurfaceRateHz)))
  {
    throw TrackingConfigurationError("igtl " + this->Opts.host + ":" +
      std::to_string(this->Opts.port) + ": expected a host, a port in 1..65535 and a rate > 0");
  }
}

void IgtlSender::Connect()
{
  this->Link.Connect(this->Opts.host, this->Opts.port, this->Opts.connectTimeout);
}

void IgtlSender::Send(const std::vector<std::uint8_t>& bytes)
{
  if (!this->Link.IsOpen())
  {
    this->Connect();
  }
  try
  {
    this->Link.WriteAll(bytes.data(), bytes.size(), this->Opts.writeTimeout);
  }
  catch (const TrackingError&)
  {
    // A half-written message would corrupt the stream: never write on this connection again.
    this->Link.Close();
    throw;
  }
  ++this->Messages;
  this->Bytes += bytes.size();
}

void IgtlSender::SendSurface(const IgtlSurface& surface, const std::string& name)
{
  this->Send(EncodeIgtlPolyData(surface, name));
  this->LastSurface = std::chrono::steady_clock::now();
  this->SentSurface = true;
}

bool IgtlSender::SendSurfaceIfDue(const IgtlSurface& surface, const std::string& name)
{
  const auto now = std::chrono::steady_clock::now();
  if (this->SentSurface &&
    std::chrono::duration<double>(now - this->LastSurface).count() <
      1.0 / this->Opts.maxSurfaceRateHz)
  {
    return false;
  }
  this->SendSurface(surface, name);
  return true;
}

void IgtlSender::SendTransform(const std::string& name,
  const Vec3& positionLps,
  const Quaternion& orientationLps)
{
  this->Send(EncodeIgtlTransformMessage(name, positionLps, orientationLps));
}

void IgtlSender::SendRibbonEnds(const RibbonSpec& ribbon, const std::string& prefix)
{
  const Quaternion start = IgtlRibbonEndFrame(ribbon.start);
  const Quaternion end = IgtlRibbonEndFrame(ribbon.end);
  this->SendTransform(prefix + "Start", ribbon.start.position, start);
  this->SendTransform(prefix + "End", ribbon.end.position, end);
}

} // namespace bender
