// Richardson extrapolation, apparent order and GCI (MeshConvergence.h) on sequences whose limit
// and order are known: f(h) = f0 + C h^p gives f0 and p back for equal and unequal refinement
// ratios; oscillatory, diverging and unchanged sequences are said, never NaN.

#include "MeshConvergence.h"

#include "BenderErrors.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{

using bender::ConvergenceKind;
using bender::EstimateMeshConvergence;
using bender::MeshSample;

std::array<MeshSample, 3> Analytic(double f0,
  double c,
  double p,
  const std::array<double, 3>& sizes)
{
  std::array<MeshSample, 3> s{};
  for (std::size_t i = 0; i < 3; ++i)
  {
    s[i] = { sizes[i], f0 + c * std::pow(sizes[i], p) };
  }
  return s;
}

void ExpectNoNaN(const bender::MeshConvergence& c)
{
  for (const double v : { c.order,
         c.extrapolated,
         c.relativeError,
         c.extrapolatedRelativeError,
         c.gci,
         c.uncertainty,
         c.ratio21,
         c.ratio32 })
  {
    EXPECT_TRUE(std::isfinite(v));
  }
  EXPECT_FALSE(c.note.empty());
}

TEST(MeshConvergence, AnalyticSequencesGiveTheirLimitAndOrderBack)
{
  const std::array<std::array<double, 3>, 4> sizeSets = { {
    { 1.0, 1.0 / std::sqrt(2.0), 0.5 }, // ratio sqrt 2 both
    { 2.0, 2.0 / 1.3, 2.0 / 1.69 },     // ratio 1.3 both (the smallest allowed)
    { 0.4, 0.25, 0.1 },                 // 1.6 then 2.5
    { 3e-4, 1.5e-4, 1.1e-4 },           // 2 then 1.36, in metres
  } };
  for (const auto& sizes : sizeSets)
  {
    for (const double p : { 0.7, 1.0, 1.5, 2.0, 3.2 })
    {
      for (const double c : { 3.0, -0.8 })
      {
        const double f0 = 137.0;
        const auto study =
          EstimateMeshConvergence(Analytic(f0, c * std::pow(sizes[0], -p), p, sizes));
        ASSERT_EQ(study.kind, ConvergenceKind::Monotone) << study.note;
        EXPECT_NEAR(study.order, p, 1e-8 * p) << "sizes " << sizes[0] << " p " << p;
        EXPECT_NEAR(study.extrapolated, f0, 1e-9 * f0);
        // The GCI bounds the finest mesh's true error with the safety factor's margin.
        const double trueError = std::fabs(study.values[0] - f0) / std::fabs(study.values[0]);
        EXPECT_NEAR(study.gci, bender::GciSafetyFactor * trueError, 1e-8);
        EXPECT_NEAR(study.extrapolatedRelativeError, std::fabs(study.values[0] - f0) / f0, 1e-9);
        ExpectNoNaN(study);
      }
    }
  }
}

TEST(MeshConvergence, TheOrderOfTheSamplesDoesNotMatter)
{
  const auto forward = Analytic(10.0, 2.0, 1.8, { 1.0, 0.6, 0.35 });
  const std::array<MeshSample, 3> shuffled = { forward[2], forward[0], forward[1] };
  const auto a = EstimateMeshConvergence(forward);
  const auto b = EstimateMeshConvergence(shuffled);
  EXPECT_EQ(a.cellSizes, b.cellSizes);
  EXPECT_EQ(a.values, b.values);
  EXPECT_DOUBLE_EQ(a.order, b.order);
  EXPECT_DOUBLE_EQ(a.extrapolated, b.extrapolated);
  EXPECT_LT(a.cellSizes[0], a.cellSizes[1]);
  EXPECT_LT(a.cellSizes[1], a.cellSizes[2]);
}

TEST(MeshConvergence, OscillatoryConvergenceIsSaidAndNotExtrapolated)
{
  const std::array<MeshSample, 3> s = { { { 1.0, 100.0 }, { 0.7, 96.0 }, { 0.5, 98.0 } } };
  const auto study = EstimateMeshConvergence(s);
  EXPECT_EQ(study.kind, ConvergenceKind::Oscillatory);
  EXPECT_EQ(study.order, 0.0);
  EXPECT_EQ(study.extrapolated, 98.0);
  EXPECT_DOUBLE_EQ(study.uncertainty, 2.0);
  EXPECT_NE(study.note.find("oscillatory"), std::string::npos);
  ExpectNoNaN(study);
}

TEST(MeshConvergence, EqualValuesAreSaidWithoutAnOrder)
{
  const std::array<MeshSample, 3> equal = { { { 1.0, 5.0 }, { 0.7, 5.0 }, { 0.5, 5.0 } } };
  const auto all = EstimateMeshConvergence(equal);
  EXPECT_EQ(all.kind, ConvergenceKind::Unchanged);
  EXPECT_EQ(all.extrapolated, 5.0);
  EXPECT_EQ(all.gci, 0.0);
  EXPECT_NE(all.note.find("equal"), std::string::npos);
  ExpectNoNaN(all);

  const std::array<MeshSample, 3> fine = { { { 1.0, 6.0 }, { 0.7, 5.0 }, { 0.5, 5.0 } } };
  const auto fineSame = EstimateMeshConvergence(fine);
  EXPECT_EQ(fineSame.kind, ConvergenceKind::Unchanged);
  ExpectNoNaN(fineSame);

  // Zero everywhere (a flow split through a closed outlet): no division by zero.
  const std::array<MeshSample, 3> zero = { { { 1.0, 0.0 }, { 0.7, 0.0 }, { 0.5, 0.0 } } };
  ExpectNoNaN(EstimateMeshConvergence(zero));
}

TEST(MeshConvergence, ChangesThatDoNotShrinkAreDiverging)
{
  // Growing changes with equal ratios: e32 / e21 < 1.
  const std::array<MeshSample, 3> growing = { { { 1.0, 10.0 }, { 0.7, 11.0 }, { 0.5, 13.0 } } };
  const auto study = EstimateMeshConvergence(growing);
  EXPECT_EQ(study.kind, ConvergenceKind::Diverging);
  EXPECT_EQ(study.extrapolated, 13.0);
  ExpectNoNaN(study);

  const std::array<MeshSample, 3> coarseSame = { { { 1.0, 10.0 }, { 0.7, 10.0 }, { 0.5, 12.0 } } };
  EXPECT_EQ(EstimateMeshConvergence(coarseSame).kind, ConvergenceKind::Diverging);
}

TEST(MeshConvergence, AFinestValueOfZeroHasNoRelativeGci)
{
  // f(h) = h^2 - 0.25: 0 on the finest mesh (h = 0.5).
  std::array<MeshSample, 3> s = Analytic(-0.25, 1.0, 2.0, { 1.0, 0.7, 0.5 });
  const auto zero = EstimateMeshConvergence(s);
  EXPECT_EQ(zero.kind, ConvergenceKind::Monotone);
  EXPECT_EQ(zero.values[0], 0.0);
  EXPECT_NEAR(zero.extrapolated, -0.25, 1e-12);
  EXPECT_EQ(zero.gci, 0.0);
  EXPECT_NEAR(zero.uncertainty, bender::GciSafetyFactor * 0.25, 1e-9);
  ExpectNoNaN(zero);
}

TEST(MeshConvergence, BadSamplesAreRefusedWithOneLine)
{
  const auto refused = [](const std::array<MeshSample, 3>& s)
  {
    try
    {
      EstimateMeshConvergence(s);
    }
    catch (const bender::InputError& e)
    {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      return true;
    }
    return false;
  };
  EXPECT_TRUE(refused({ { { 1.0, 1.0 }, { 0.9, 2.0 }, { 0.5, 3.0 } } })); // ratio 1.11
  EXPECT_TRUE(refused({ { { 1.0, 1.0 }, { 0.7, 2.0 }, { 0.7, 3.0 } } })); // the same mesh twice
  EXPECT_TRUE(refused({ { { 0.0, 1.0 }, { 0.7, 2.0 }, { 0.5, 3.0 } } }));
  EXPECT_TRUE(refused({ { { -1.0, 1.0 }, { 0.7, 2.0 }, { 0.5, 3.0 } } }));
  EXPECT_TRUE(refused({ { { 1.0, NAN }, { 0.7, 2.0 }, { 0.5, 3.0 } } }));
  EXPECT_TRUE(refused({ { { INFINITY, 1.0 }, { 0.7, 2.0 }, { 0.5, 3.0 } } }));
  EXPECT_FALSE(refused({ { { 1.69, 1.0 }, { 1.3, 2.0 }, { 1.0, 2.5 } } })); // 1.3 is allowed
}

} // namespace

TEST(MeshConvergence, TheCoarsestMeshIsMeasuredFromTheBestEstimate)
{
  // Monotone: from the extrapolated value (f0 = 10, f = 10 + 2 h^2).
  const auto monotone = EstimateMeshConvergence(Analytic(10.0, 2.0, 2.0, { 1.0, 1.3, 1.69 }));
  ASSERT_EQ(monotone.kind, ConvergenceKind::Monotone);
  ASSERT_TRUE(bender::CoarsestDeviation(monotone).has_value());
  EXPECT_NEAR(*bender::CoarsestDeviation(monotone), (10.0 + 2.0 * 1.69 * 1.69 - 10.0) / 10.0, 1e-9);
  // Oscillatory: from the finest value (coarsest 100, finest 98).
  const std::array<MeshSample, 3> s = { { { 1.0, 100.0 }, { 0.7, 96.0 }, { 0.5, 98.0 } } };
  ASSERT_TRUE(bender::CoarsestDeviation(EstimateMeshConvergence(s)).has_value());
  EXPECT_DOUBLE_EQ(*bender::CoarsestDeviation(EstimateMeshConvergence(s)), 2.0 / 98.0);
  // Unchanged on the two finest: from the finest value.
  const std::array<MeshSample, 3> fine = { { { 1.0, 6.0 }, { 0.7, 5.0 }, { 0.5, 5.0 } } };
  EXPECT_DOUBLE_EQ(bender::CoarsestDeviation(EstimateMeshConvergence(fine)).value_or(-1.0), 0.2);
  // Diverging, or a best estimate of 0: none.
  const std::array<MeshSample, 3> diverging = { { { 1.0, 1.0 }, { 0.7, 2.0 }, { 0.5, 4.0 } } };
  ASSERT_EQ(EstimateMeshConvergence(diverging).kind, ConvergenceKind::Diverging);
  EXPECT_FALSE(bender::CoarsestDeviation(EstimateMeshConvergence(diverging)).has_value());
  const std::array<MeshSample, 3> zero = { { { 1.0, 0.0 }, { 0.7, 0.0 }, { 0.5, 0.0 } } };
  EXPECT_FALSE(bender::CoarsestDeviation(EstimateMeshConvergence(zero)).has_value());
}
