// CSG on sorted depth lists (habuffer/csg.h): the expression's grammar and
// errors, and the walk over a pixel's records, with touching and coplanar
// solids and more primitives than one word of bits.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "habuffer/csg.h"

namespace habuffer {
namespace {

const std::vector<std::string> kNames = {"a", "b", "c", "cube_1"};

std::string error_of(const std::string& text) {
  try {
    (void)CsgExpression::parse(text, kNames);
  } catch (const CsgError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(Csg, IntersectionBindsTighterAndUnionAndDifferenceAssociateLeft) {
  EXPECT_EQ(CsgExpression::parse("a - b | c", kNames).text(), "((a - b) | c)");
  EXPECT_EQ(CsgExpression::parse("a | b & c", kNames).text(), "(a | (b & c))");
  EXPECT_EQ(CsgExpression::parse("a - (b + c) * cube_1", kNames).text(), "(a - ((b | c) & cube_1))");
  EXPECT_EQ(CsgExpression::parse("  ((a))  ", kNames).text(), "a");
}

TEST(Csg, BadExpressionsAreRefusedNamingTheTokenAndColumn) {
  EXPECT_EQ(error_of("a - d"), "csg expression, column 5: unknown primitive 'd'");
  EXPECT_EQ(error_of("a |"), "csg expression, column 4: expected a primitive at the end");
  EXPECT_EQ(error_of("(a | b"), "csg expression, column 7: expected ')' at the end");
  EXPECT_EQ(error_of("a $ b"), "csg expression, column 3: unexpected '$'");
  EXPECT_EQ(error_of("a | | b"), "csg expression, column 5: expected a primitive or '(', not '|'");
  EXPECT_EQ(error_of("   "), "csg expression: empty");
  EXPECT_NE(error_of(std::string(2000, '(') + "a" + std::string(2000, ')')).find("nesting deeper than 1000"),
            std::string::npos);
  EXPECT_THROW((void)CsgExpression::parse("a", std::vector<std::string>(kMaxCsgPrimitives + 1, "a")), CsgError);
}

TEST(Csg, EvaluationFollowsTheOperatorsTruthTables) {
  const CsgExpression e = CsgExpression::parse("(a - b) | (b & c)", kNames);
  for (int m = 0; m < 8; ++m) {
    CsgInside in(4);
    in.set(0, m & 1);
    in.set(1, m & 2);
    in.set(2, m & 4);
    const bool a = m & 1, b = m & 2, c = m & 4;
    EXPECT_EQ(e.evaluate(in), (a && !b) || (b && c)) << "mask " << m;
  }
}

ListEntry crossing(std::uint32_t code, std::uint32_t id, bool exit) { return {0, code, csg_data(id, exit)}; }

TEST(Csg, TheWalkShowsTheFirstDepthWhereTheExpressionTurnsTrue) {
  // a spans codes 800..200, b 600..400 (nearest first: codes falling).
  const std::vector<ListEntry> list = {crossing(800, 0, false), crossing(600, 1, false), crossing(400, 1, true),
                                       crossing(200, 0, true)};
  const auto resolve = [&](const char* text) { return csg_resolve(list, CsgExpression::parse(text, kNames)); };
  const CsgSurface minus = resolve("a - b");
  EXPECT_TRUE(minus.visible);
  EXPECT_EQ(minus.code, 800u);
  EXPECT_EQ(minus.primitive, 0u);
  EXPECT_FALSE(resolve("b - a").visible);  // b lies inside a
  const CsgSurface both = resolve("a & b");
  EXPECT_EQ(both.code, 600u);
  EXPECT_EQ(both.primitive, 1u);
  EXPECT_FALSE(resolve("c").visible);
}

TEST(Csg, CoplanarAndTouchingSolidsDoNotDependOnTheRecordsOrderAtOneDepth) {
  // b enters where a does: a - b shows nothing there, then b's far side.
  for (const bool a_first : {true, false}) {
    std::vector<ListEntry> list = {crossing(800, 0, false), crossing(800, 1, false), crossing(400, 1, true),
                                   crossing(200, 0, true)};
    if (!a_first) std::swap(list[0], list[1]);
    const CsgSurface s = csg_resolve(list, CsgExpression::parse("a - b", kNames));
    EXPECT_TRUE(s.visible);
    EXPECT_EQ(s.code, 400u);
    EXPECT_EQ(s.primitive, 1u);
    EXPECT_TRUE(s.exit);
  }
  // a's exit and b's entry at one depth: a | b shows a's entry only, a & b nothing.
  const std::vector<ListEntry> touching = {crossing(800, 0, false), crossing(500, 1, false), crossing(500, 0, true),
                                           crossing(200, 1, true)};
  const CsgSurface u = csg_resolve(touching, CsgExpression::parse("a | b", kNames));
  EXPECT_EQ(u.code, 800u);
  EXPECT_FALSE(csg_resolve(touching, CsgExpression::parse("a & b", kNames)).visible);
}

// Coplanar faces rounded a few codes apart (the GPU interpolates each
// triangle's depth): within `coincident` codes they are one depth.
TEST(Csg, CrossingsWithinTheCoincidenceWindowAreOneDepth) {
  const std::vector<ListEntry> list = {crossing(803, 0, false), crossing(800, 1, false), crossing(400, 1, true),
                                       crossing(200, 0, true)};
  const CsgExpression e = CsgExpression::parse("a - b", kNames);
  EXPECT_EQ(csg_resolve(list, e).code, 803u);  // a's face 3 codes nearer shows for a sliver
  const CsgSurface s = csg_resolve(list, e, 4);
  EXPECT_EQ(s.code, 400u);  // one depth: the hole's far side
  EXPECT_EQ(s.primitive, 1u);
}

TEST(Csg, MoreThanSixtyFourPrimitivesAreWalkedWithAWordPerSixtyFour) {
  std::vector<std::string> names = {"box"};
  std::string text = "box - (";
  for (int i = 1; i <= 200; ++i) {
    names.push_back("cyl" + std::to_string(i));
    text += (i > 1 ? " | " : "") + names.back();
  }
  text += ")";
  const CsgExpression e = CsgExpression::parse(text, names);
  EXPECT_EQ(e.primitives(), 201u);
  // The box from 900 to 100; cylinder 150 covers 950..50 (a hole through it here).
  std::vector<ListEntry> hole = {crossing(950, 150, false), crossing(900, 0, false), crossing(100, 0, true),
                                 crossing(50, 150, true)};
  EXPECT_FALSE(csg_resolve(hole, e).visible);
  // Cylinder 199 only dents it: from 950 to 700, so the box shows at 700, the cylinder's far side.
  std::vector<ListEntry> dent = {crossing(950, 199, false), crossing(900, 0, false), crossing(700, 199, true),
                                 crossing(100, 0, true)};
  const CsgSurface s = csg_resolve(dent, e);
  EXPECT_EQ(s.code, 700u);
  EXPECT_EQ(s.primitive, 199u);
  const std::vector<ListEntry> bad = {crossing(900, 201, false)};
  EXPECT_THROW((void)csg_resolve(bad, e), CsgError);
}

}  // namespace
}  // namespace habuffer
