#include "RibbonPlacement.h"
#include "LogicTestUtilities.h"
#include "RibbonWarp.h"

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
