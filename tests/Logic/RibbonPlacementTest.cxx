#include "RibbonPlacement.h"
#include "GeometryErrors.h"
#include "LogicTestUtilities.h"
#include "RibbonWarp.h"
#include "SessionAutosave.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace bender;

TEST(RibbonPlacement, LiesOnTheAxisOfATube)
{
  // A tube of radius 3 along x, picked on its wall.
  auto tube = test::MakeTube(0, 80, 3, 161, 32);
  const RibbonPlacement placement = PlaceRibbonOnSurface(tube, { 41, 0, 3 });
  EXPECT_NEAR(placement.vesselRadius, 3.0, 0.3);
  EXPECT_NEAR(placement.suggestedRadius, 2.2 * placement.vesselRadius, 1e-9);
  const Vec3 axis = Normalized(placement.ribbon.end.position - placement.ribbon.start.position);
  EXPECT_GT(std::abs(axis.x), 0.99);
  const Vec3 middle = 0.5 * (placement.ribbon.start.position + placement.ribbon.end.position);
  EXPECT_NEAR(middle.y, 0.0, 0.2);
  EXPECT_NEAR(middle.z, 0.0, 0.2);
  EXPECT_NEAR(middle.x, 41.0, 1.0);
  EXPECT_NEAR(Norm(placement.ribbon.end.position - placement.ribbon.start.position),
    8.0 * placement.vesselRadius,
    1e-9);
  // The ribbon is valid and can be grabbed as is.
  WarpSpec warp;
  warp.initial = warp.final = placement.ribbon;
  warp.radius = placement.suggestedRadius;
  EXPECT_NO_THROW(RibbonWarp::Validate(warp));
}

TEST(RibbonPlacement, RefusesUnusablePicks)
{
  auto tube = test::MakeTube(0, 80, 3, 161, 32);
  EXPECT_THROW(PlaceRibbonOnSurface(nullptr, { 0, 0, 0 }), RibbonPlacementError);
  EXPECT_THROW(PlaceRibbonOnSurface(tube, { std::nan(""), 0, 0 }), RibbonPlacementError);
  EXPECT_THROW(PlaceRibbonOnSurface(tube, { 500, 500, 500 }), RibbonPlacementError);
  RibbonPlacementOptions options;
  options.lengthFactor = 100;
  EXPECT_THROW(PlaceRibbonOnSurface(tube, { 40, 0, 3 }, options), RibbonPlacementError);
}

// The errors of Logic and of the geometry core are InputErrors: a caller (the CLI, the
// session) catches bender::Error once, with no catch-all re-wrap in between.
TEST(LogicErrors, AreRootedAtInputError)
{
  EXPECT_THROW(PlaceRibbonOnSurface(nullptr, { 0, 0, 0 }), InputError);
  EXPECT_THROW(ReadSessionFile("/nonexistent/bender-session.json"), InputError);
  WarpSpec warp; // coincident ends: no wire
  warp.radius = 10.0;
  try
  {
    RibbonWarp::Validate(warp);
    FAIL() << "a ribbon with coincident ends was accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(dynamic_cast<const GeometryError*>(&e), nullptr) << e.what();
  }
}
