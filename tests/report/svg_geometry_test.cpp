// Pixel geometry of the SVG plots (report/svg_geometry.h): Liang–Barsky clipping against
// closed-form intersections and against a brute-force scan of the segment, clipped polylines
// as path data, and the obstacle count that places labels.

#include "report/svg_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <vector>

namespace imunoise::report::svg_detail {
namespace {

constexpr Rect kSquare{0.0, 0.0, 10.0, 10.0};

TEST(SvgClipSegment, InsideSegmentIsUnchanged) {
  Point a{1.0, 2.0}, b{9.0, 7.5};
  ASSERT_TRUE(clip_segment(a, b, kSquare));
  EXPECT_EQ(a.x, 1.0);
  EXPECT_EQ(a.y, 2.0);
  EXPECT_EQ(b.x, 9.0);
  EXPECT_EQ(b.y, 7.5);
}

TEST(SvgClipSegment, CutsAtTheEdgesItCrosses) {
  // Horizontal y = 5 from x = -10 to 30 on [0, 20] x [0, 10]: cut at x = 0 and x = 20.
  Point a{-10.0, 5.0}, b{30.0, 5.0};
  ASSERT_TRUE(clip_segment(a, b, Rect{0.0, 0.0, 20.0, 10.0}));
  EXPECT_DOUBLE_EQ(a.x, 0.0);
  EXPECT_DOUBLE_EQ(a.y, 5.0);
  EXPECT_DOUBLE_EQ(b.x, 20.0);
  EXPECT_DOUBLE_EQ(b.y, 5.0);
  // The diagonal y = x from (-5, -5) to (15, 15): the square's corners (0, 0) and (10, 10).
  Point c{-5.0, -5.0}, d{15.0, 15.0};
  ASSERT_TRUE(clip_segment(c, d, kSquare));
  EXPECT_DOUBLE_EQ(c.x, 0.0);
  EXPECT_DOUBLE_EQ(c.y, 0.0);
  EXPECT_DOUBLE_EQ(d.x, 10.0);
  EXPECT_DOUBLE_EQ(d.y, 10.0);
  // y = 2x + 1 from (-2, -3) to (2, 5) meets y = 0 at x = -1/2, left of the square, so it
  // enters through x = 0 at y = 1; its end (2, 5) is inside and stays.
  Point e{-2.0, -3.0}, f{2.0, 5.0};
  ASSERT_TRUE(clip_segment(e, f, kSquare));
  EXPECT_DOUBLE_EQ(e.x, 0.0);
  EXPECT_DOUBLE_EQ(e.y, 1.0);
  EXPECT_EQ(f.x, 2.0);
  EXPECT_EQ(f.y, 5.0);
}

TEST(SvgClipSegment, NothingLeftOutside) {
  Point a{-5.0, -1.0}, b{15.0, -1.0};  // parallel to the top edge, above it
  EXPECT_FALSE(clip_segment(a, b, kSquare));
  Point c{-5.0, 4.0}, d{4.0, -5.0};  // x + y = -1 passes by the corner (0, 0)
  EXPECT_FALSE(clip_segment(c, d, kSquare));
  Point e{11.0, 11.0}, f{11.0, 11.0};  // a point outside
  EXPECT_FALSE(clip_segment(e, f, kSquare));
}

TEST(SvgClipSegment, AlongAnEdgeIsKept) {
  Point a{-5.0, 0.0}, b{15.0, 0.0};
  ASSERT_TRUE(clip_segment(a, b, kSquare));
  EXPECT_DOUBLE_EQ(a.x, 0.0);
  EXPECT_DOUBLE_EQ(b.x, 10.0);
  EXPECT_EQ(a.y, 0.0);
  EXPECT_EQ(b.y, 0.0);
}

// Independent truth: the part of the segment inside the (convex) rectangle is the interval of
// parameters t whose points a + t (b - a) lie inside; scanned at 20001 values of t.
TEST(SvgClipSegment, MatchesABruteForceScanOfRandomSegments) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> coordinate(-20.0, 30.0);
  constexpr int kSteps = 20000;
  for (int trial = 0; trial < 2000; ++trial) {
    const Point a0{coordinate(rng), coordinate(rng)}, b0{coordinate(rng), coordinate(rng)};
    const double length = std::hypot(b0.x - a0.x, b0.y - a0.y);
    const double step = length / kSteps;
    std::optional<int> first, last;
    for (int k = 0; k <= kSteps; ++k) {
      const double t = static_cast<double>(k) / kSteps;
      if (kSquare.contains({a0.x + t * (b0.x - a0.x), a0.y + t * (b0.y - a0.y)})) {
        if (!first) first = k;
        last = k;
      }
    }
    Point a = a0, b = b0;
    const bool kept = clip_segment(a, b, kSquare);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << ": (" << a0.x << ", " << a0.y
                                      << ") - (" << b0.x << ", " << b0.y << ")");
    if (!kept) {
      EXPECT_FALSE(first.has_value());
      continue;
    }
    if (!first) {  // a piece shorter than the scan step
      EXPECT_LE(std::hypot(b.x - a.x, b.y - a.y), step + 1e-9);
      continue;
    }
    const double t_first = static_cast<double>(*first) / kSteps;
    const double t_last = static_cast<double>(*last) / kSteps;
    const double tolerance = step + 1e-9;
    EXPECT_NEAR(a.x, a0.x + t_first * (b0.x - a0.x), tolerance);
    EXPECT_NEAR(a.y, a0.y + t_first * (b0.y - a0.y), tolerance);
    EXPECT_NEAR(b.x, a0.x + t_last * (b0.x - a0.x), tolerance);
    EXPECT_NEAR(b.y, a0.y + t_last * (b0.y - a0.y), tolerance);
  }
}

TEST(SvgPolylinePath, OneSubpathPerVisibleRun) {
  // Enters through the left edge, turns down and leaves through the bottom edge.
  EXPECT_EQ(polyline_path({Point{-10.0, 5.0}, Point{5.0, 5.0}, Point{5.0, 20.0}}, kSquare),
            "M0 5 5 5 5 10");
  // A gap (nullopt) lifts the pen.
  EXPECT_EQ(polyline_path(
                {Point{1.0, 1.0}, Point{2.0, 2.0}, std::nullopt, Point{3.0, 3.0}, Point{4.0, 4.0}},
                kSquare),
            "M1 1 2 2 M3 3 4 4");
  // Leaves through the right edge and comes back at y = 5.5: a new subpath where it re-enters.
  EXPECT_EQ(polyline_path({Point{5.0, 5.0}, Point{15.0, 5.0}, Point{5.0, 6.0}}, kSquare),
            "M5 5 10 5 M10 5.5 5 6");
  EXPECT_EQ(polyline_path({Point{-5.0, -1.0}, Point{15.0, -1.0}}, kSquare), "");
  EXPECT_EQ(polyline_path({Point{5.0, 5.0}}, kSquare), "");
}

TEST(SvgObstacles, CountsCrossingSegmentsAndOverlappingBoxes) {
  Obstacles obstacles;
  obstacles.segments.emplace_back(Point{-5.0, 5.0}, Point{15.0, 5.0});    // crosses
  obstacles.segments.emplace_back(Point{-5.0, -5.0}, Point{-1.0, 20.0});  // passes by
  obstacles.boxes.push_back({5.0, 5.0, 15.0, 15.0});                      // overlaps
  obstacles.boxes.push_back({10.0, 0.0, 20.0, 10.0});                     // touches only
  EXPECT_EQ(obstacles.hits(kSquare), 2);
  obstacles.add_polyline({Point{2.0, -5.0}, Point{2.0, 15.0}, std::nullopt, Point{3.0, 3.0}});
  EXPECT_EQ(obstacles.segments.size(), 3u);  // the gap adds nothing
  EXPECT_EQ(obstacles.hits(kSquare), 3);
}

TEST(SvgRect, InsideOverlapsAndBoxAround) {
  EXPECT_TRUE(inside(Rect{0.0, 0.0, 10.0, 10.0}, kSquare));
  EXPECT_FALSE(inside(Rect{-0.5, 1.0, 5.0, 5.0}, kSquare));
  EXPECT_TRUE(overlaps(Rect{9.0, 9.0, 11.0, 11.0}, kSquare));
  EXPECT_FALSE(overlaps(Rect{10.0, 0.0, 11.0, 10.0}, kSquare));
  const Rect box = box_around({3.0, 4.0}, 1.5);
  EXPECT_EQ(box.left, 1.5);
  EXPECT_EQ(box.top, 2.5);
  EXPECT_EQ(box.right, 4.5);
  EXPECT_EQ(box.bottom, 5.5);
  EXPECT_TRUE(kSquare.contains({10.2, 5.0}, 0.5));
  EXPECT_FALSE(kSquare.contains({10.2, 5.0}));
}

}  // namespace
}  // namespace imunoise::report::svg_detail
