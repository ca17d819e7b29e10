// The public conformance vectors of the independent implementation of the spec
// (tests/data/conformance): frames, screws and warped tube positions must agree.

#include "GeometryTestUtilities.h"
#include "RibbonWarp.h"
#include "WarpBinding.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace
{
using bender::Vec3;
using nlohmann::json;

const std::string DataDir = std::string(BENDER_TEST_DATA_DIR) + "/conformance/";

Vec3 V(const json& a)
{
  return { a.at(0).get<double>(), a.at(1).get<double>(), a.at(2).get<double>() };
}

bender::RibbonSpec RibbonFromJson(const json& j)
{
  bender::RibbonSpec r;
  r.start = {
    V(j.at("start").at("position")), V(j.at("start").at("tangent")), V(j.at("start").at("normal"))
  };
  r.end = {
    V(j.at("end").at("position")), V(j.at("end").at("tangent")), V(j.at("end").at("normal"))
  };
  r.extraTurns = j.value("extraTurns", 0);
  return r;
}

// The conformance plans are valid by construction; the project's full reader with every
// rejection rule is tested in tests/IO.
std::vector<bender::WarpSpec> LoadWarps(const std::string& name)
{
  std::ifstream in(DataDir + name + ".bender.json");
  const json plan = json::parse(in);
  std::vector<bender::WarpSpec> warps;
  for (const json& w : plan.at("warps"))
  {
    bender::WarpSpec s;
    s.initial = RibbonFromJson(w.at("initial"));
    s.final = RibbonFromJson(w.at("final"));
    s.radius = w.at("radius").get<double>();
    const json decay = w.value("decay", json::object());
    s.decay.shape = decay.value("shape", "bell") == "plateau" ? bender::DecayShape::Plateau
                                                              : bender::DecayShape::Bell;
    s.decay.plateau = decay.value("plateau", 0.5);
    s.reverseScrews = w.value("reverseScrews", false);
    warps.push_back(s);
  }
  return warps;
}

bender::Frame FrameFromJson(const json& j)
{
  return { V(j.at("P")), V(j.at("T")), V(j.at("N")), V(j.at("B")) };
}

class Conformance : public ::testing::TestWithParam<std::string>
{
};

TEST_P(Conformance, FramesScrewsAndWireMatchTheIndependentImplementation)
{
  const auto warps = LoadWarps(GetParam());
  std::ifstream in(DataDir + GetParam() + ".frames.jsonl");
  ASSERT_TRUE(in) << "missing frames file";
  std::string line;
  std::vector<bender::RibbonWarp> built;
  for (const auto& w : warps)
  {
    built.emplace_back(w);
  }
  int lines = 0;
  while (std::getline(in, line))
  {
    const json j = json::parse(line);
    const int wi = j.at("warp").get<int>();
    ASSERT_LT(wi, static_cast<int>(built.size()));
    const bender::RibbonWarp& warp = built[wi];
    if (j.contains("a"))
    {
      // Header line: tangent lengths, junction parameters, twists, r_min.
      const bender::Ribbon* rib[2] = { &warp.Initial(), &warp.Final() };
      for (int k = 0; k < 2; ++k)
      {
        const json& a = j.at("a").at(k);
        if (!a.is_null())
        {
          EXPECT_NEAR(rib[k]->Wire().TangentLength(), a.get<double>(), 1e-9);
        }
        EXPECT_NEAR(rib[k]->Wire().JunctionParameter(), j.at("sJ").at(k).get<double>(), 1e-12);
        EXPECT_NEAR(rib[k]->Twist(), j.at("tau").at(k).get<double>(), 1e-12);
      }
      if (j.at("rmin").is_null())
      {
        EXPECT_TRUE(std::isinf(warp.InitialMinimumRadius()));
      }
      else
      {
        EXPECT_NEAR(warp.InitialMinimumRadius(), j.at("rmin").get<double>(), 1e-9);
      }
      continue;
    }
    ++lines;
    const double s = j.at("s").get<double>();
    const bender::Frame ci = warp.Initial().FrameAt(s);
    const bender::Frame cf = warp.Final().FrameAt(s);
    EXPECT_LT(bendertest::MaxDeviation(ci, FrameFromJson(j.at("initial"))), 1e-9)
      << GetParam() << " warp " << wi << " s=" << s;
    EXPECT_LT(bendertest::MaxDeviation(cf, FrameFromJson(j.at("final"))), 1e-9)
      << GetParam() << " warp " << wi << " s=" << s;
    const bender::Screw screw = warp.ScrewAt(s);
    const json& js = j.at("screw");
    EXPECT_NEAR(screw.beta, js.at("beta").get<double>(), 1e-9) << "s=" << s;
    EXPECT_NEAR(screw.d, js.at("d").get<double>(), 1e-9) << "s=" << s;
    EXPECT_EQ(screw.flipped, js.at("flipped").get<bool>()) << "s=" << s;
    if (js.at("beta").get<double>() > 1e-9)
    {
      EXPECT_LT(bender::Distance(screw.k, V(js.at("K"))), 1e-9) << "s=" << s;
    }
  }
  EXPECT_EQ(lines, 101 * static_cast<int>(warps.size()));
}

TEST_P(Conformance, WarpedTubeMatchesExpectedPositions)
{
  const auto warps = LoadWarps(GetParam());
  bendertest::Mesh mesh = bendertest::ReadOff(DataDir + "tube.off");
  const bendertest::Mesh expected = bendertest::ReadOff(DataDir + GetParam() + ".expected.off");
  ASSERT_EQ(mesh.points.size(), expected.points.size());
  for (const auto& spec : warps)
  {
    const bender::RibbonWarp warp(spec);
    for (Vec3& p : mesh.points)
    {
      p = warp.Apply(p);
    }
  }
  // Tube size: 50 mm long. Exact double evaluation agrees within 1e-9 of the size.
  const double tol = 1e-9 * 50.0;
  double worst = 0.0;
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    worst = std::max(worst, bender::Distance(mesh.points[i], expected.points[i]));
  }
  EXPECT_LT(worst, tol) << GetParam();
}

TEST_P(Conformance, BindingAndTableEvaluationAgree)
{
  // The per-grab binding with exact evaluation reproduces the expected result exactly;
  // the interactive table path stays within the spec's 1e-5 of the tube's size.
  const auto warps = LoadWarps(GetParam());
  bendertest::Mesh mesh = bendertest::ReadOff(DataDir + "tube.off");
  const bendertest::Mesh expected = bendertest::ReadOff(DataDir + GetParam() + ".expected.off");
  std::vector<double> exact, table;
  for (const auto& p : mesh.points)
  {
    exact.insert(exact.end(), { p.x, p.y, p.z });
  }
  table = exact;
  for (const auto& spec : warps)
  {
    const bender::RibbonWarp warp(spec);
    for (auto* xyz : { &exact, &table })
    {
      const std::size_t n = xyz->size() / 3;
      bender::WarpBinding binding(spec, bender::BlendMode::TwoProjections);
      std::vector<bender::BoundPoint> rec(n);
      std::vector<std::uint8_t> bound(n);
      binding.BindRange(xyz->data(), 0, n, rec.data(), bound.data());
      std::vector<std::int64_t> ids;
      for (std::size_t i = 0; i < n; ++i)
      {
        if (bound[i])
        {
          ids.push_back(static_cast<std::int64_t>(i));
        }
      }
      const bender::WarpEvaluator eval(
        warp, xyz == &exact ? bender::WarpPrecision::Exact : bender::WarpPrecision::Table);
      std::vector<double> out = *xyz;
      eval.EvaluateRange(
        bender::WarpBatch<double>{ xyz->data(), out.data(), rec.data(), ids.data() },
        0,
        ids.size());
      *xyz = out;
    }
  }
  double worstExact = 0.0, worstTable = 0.0;
  for (std::size_t i = 0; i < expected.points.size(); ++i)
  {
    const Vec3 e = expected.points[i];
    worstExact = std::max(
      worstExact, bender::Distance(e, { exact[3 * i], exact[3 * i + 1], exact[3 * i + 2] }));
    worstTable = std::max(
      worstTable, bender::Distance(e, { table[3 * i], table[3 * i + 1], table[3 * i + 2] }));
  }
  EXPECT_LT(worstExact, 1e-9 * 50.0);
  EXPECT_LT(worstTable, 1e-5 * 50.0);
}

INSTANTIATE_TEST_SUITE_P(Vectors,
  Conformance,
  ::testing::Values("bend90", "twist150", "semicircle_chain"));

} // namespace
