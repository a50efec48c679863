// Central composite designs: the paper's Tables 3–4 (Zhao et al. 2023), point counts and α
// for other designs, standard order and the seeded random order.
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "doe/central_composite_design.hpp"

namespace regodem::doe {
namespace {

const std::vector<DesignFactor> paper_factors = {{"C_wall", "J/(kg K)", 1200.0, 600.0},
                                                 {"lambda_wall", "W/(m K)", 300.0, 200.0}};

CcdOptions with_centre_points(int n) {
  CcdOptions options;
  options.centre_points = n;
  return options;
}

TEST(CentralCompositeDesign, PaperTables3And4AsASetOfPoints) {
  const CentralCompositeDesign design = make_central_composite_design(paper_factors, with_centre_points(3));
  EXPECT_DOUBLE_EQ(design.alpha, std::sqrt(2.0));  // (2²)^(1/4)
  ASSERT_EQ(design.runs.size(), 11U);
  // Table 3 (W1–W11); the paper rounds the ±α levels 351.47/2048.53 and 17.16/582.84 down.
  std::vector<std::pair<double, double>> paper = {{1200, 17},  {1200, 300}, {2048, 300}, {1200, 300},
                                                  {1800, 100}, {600, 500},  {1800, 500}, {1200, 582},
                                                  {351, 300},  {600, 100},  {1200, 300}};
  std::vector<std::pair<double, double>> ours;
  for (const DesignPoint& p : design.runs) ours.emplace_back(p.actual[0], p.actual[1]);
  // Match as multisets: each of ours takes the first unused paper point within the rounding.
  std::vector<bool> used(paper.size(), false);
  for (const auto& [c, lambda] : ours) {
    bool matched = false;
    for (std::size_t i = 0; i < paper.size() && !matched; ++i)
      if (!used[i] && std::fabs(c - paper[i].first) < 1.0 && std::fabs(lambda - paper[i].second) < 1.0)
        used[i] = matched = true;
    EXPECT_TRUE(matched) << "no Table 3 run matches (" << c << ", " << lambda << ")";
  }
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));

  // Table 4: coded levels −α, −1, 0, +1, +α with their actual values.
  const double a = std::sqrt(2.0);
  std::map<double, std::pair<double, double>> levels;
  for (const DesignPoint& p : design.runs)
    for (std::size_t f = 0; f < 2; ++f) {
      auto& level = levels[p.coded[f]];
      (f == 0 ? level.first : level.second) = p.actual[f];
    }
  ASSERT_EQ(levels.size(), 5U);
  const std::vector<double> coded = {-a, -1.0, 0.0, 1.0, a};
  const std::vector<std::pair<double, double>> table4 = {{351, 17}, {600, 100}, {1200, 300}, {1800, 500}, {2048, 582}};
  for (std::size_t l = 0; l < coded.size(); ++l) {
    ASSERT_EQ(levels.count(coded[l]), 1U) << coded[l];  // coded values exact
    EXPECT_LT(std::fabs(levels[coded[l]].first - table4[l].first), 1.0);
    EXPECT_LT(std::fabs(levels[coded[l]].second - table4[l].second), 1.0);
  }
}

TEST(CentralCompositeDesign, StandardOrderAndPointTypes) {
  const CentralCompositeDesign design = make_central_composite_design(paper_factors, with_centre_points(3));
  const std::vector<std::vector<double>> expected_coded = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};  // Yates order
  for (std::size_t r = 0; r < 4; ++r) {
    EXPECT_EQ(design.runs[r].type, PointType::factorial);
    EXPECT_EQ(design.runs[r].coded, expected_coded[r]);
  }
  const double a = std::sqrt(2.0);
  EXPECT_EQ(design.runs[4].coded, (std::vector<double>{-a, 0}));
  EXPECT_EQ(design.runs[5].coded, (std::vector<double>{a, 0}));
  EXPECT_EQ(design.runs[6].coded, (std::vector<double>{0, -a}));
  EXPECT_EQ(design.runs[7].coded, (std::vector<double>{0, a}));
  for (std::size_t r = 4; r < 8; ++r) EXPECT_EQ(design.runs[r].type, PointType::axial);
  for (std::size_t r = 8; r < 11; ++r) EXPECT_EQ(design.runs[r].type, PointType::centre);
  for (std::size_t r = 0; r < 11; ++r) EXPECT_EQ(design.runs[r].standard_order, static_cast<int>(r + 1));
  EXPECT_DOUBLE_EQ(design.runs[0].actual[0], 600.0);
  EXPECT_DOUBLE_EQ(design.runs[0].actual[1], 100.0);
}

TEST(CentralCompositeDesign, FaceCentredAndThreeFactors) {
  CcdOptions face = with_centre_points(2);
  face.alpha_kind = AlphaKind::face;
  const CentralCompositeDesign d2 = make_central_composite_design(paper_factors, face);
  EXPECT_EQ(d2.alpha, 1.0);
  EXPECT_EQ(d2.runs.size(), 4U + 4U + 2U);
  for (const DesignPoint& p : d2.runs)
    for (double c : p.coded) EXPECT_LE(std::fabs(c), 1.0);

  const std::vector<DesignFactor> three = {{"A", "", 0, 1}, {"B", "", 10, 2}, {"C", "", -5, 0.5}};
  const CentralCompositeDesign d3 = make_central_composite_design(three, with_centre_points(6));
  EXPECT_EQ(d3.factorial_points, 8);
  EXPECT_EQ(d3.axial_points, 6);
  EXPECT_EQ(d3.runs.size(), 8U + 6U + 6U);
  EXPECT_NEAR(d3.alpha, std::pow(8.0, 0.25), 1e-15);  // 1.68179
  EXPECT_DOUBLE_EQ(d3.runs[8 + 3].actual[1], 10.0 + 2.0 * d3.alpha);  // +α on B

  CcdOptions given = with_centre_points(0);
  given.alpha_kind = AlphaKind::given;
  given.alpha = 2.0;
  EXPECT_EQ(make_central_composite_design(three, given).alpha, 2.0);
}

TEST(CentralCompositeDesign, HalfFractionForFiveFactors) {
  std::vector<DesignFactor> five;
  for (const char* name : {"A", "B", "C", "D", "E"}) five.push_back({name, "", 0, 1});
  CcdOptions half = with_centre_points(1);
  half.half_fraction = true;
  const CentralCompositeDesign design = make_central_composite_design(five, half);
  EXPECT_EQ(design.factorial_points, 16);
  EXPECT_NEAR(design.alpha, 2.0, 1e-15);  // 16^(1/4): the rule uses the runs actually in the factorial part
  EXPECT_EQ(design.runs.size(), 16U + 10U + 1U);
  for (int r = 0; r < 16; ++r) {  // defining relation I = ABCDE
    double product = 1.0;
    for (double c : design.runs[static_cast<std::size_t>(r)].coded) product *= c;
    EXPECT_EQ(product, 1.0);
  }
  EXPECT_THROW(make_central_composite_design(std::vector<DesignFactor>(five.begin(), five.begin() + 4), half),
               InputError);
}

TEST(CentralCompositeDesign, RandomOrderIsASeededPermutation) {
  CcdOptions random = with_centre_points(3);
  random.order = RunOrder::random;
  random.seed = 42;
  const CentralCompositeDesign a = make_central_composite_design(paper_factors, random);
  const CentralCompositeDesign b = make_central_composite_design(paper_factors, random);
  random.seed = 43;
  const CentralCompositeDesign c = make_central_composite_design(paper_factors, random);
  std::vector<int> orders_a, orders_b, orders_c;
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    orders_a.push_back(a.runs[r].standard_order);
    orders_b.push_back(b.runs[r].standard_order);
    orders_c.push_back(c.runs[r].standard_order);
  }
  EXPECT_EQ(orders_a, orders_b);
  EXPECT_NE(orders_a, orders_c);
  std::vector<int> sorted = orders_a;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < 11; ++i) EXPECT_EQ(sorted[static_cast<std::size_t>(i)], i + 1);
  // Each run keeps its values: the standard-order design at that position.
  const CentralCompositeDesign standard = make_central_composite_design(paper_factors, with_centre_points(3));
  for (const DesignPoint& p : a.runs) EXPECT_EQ(p.coded, standard.runs[static_cast<std::size_t>(p.standard_order - 1)].coded);
}

TEST(CentralCompositeDesign, RefusesBadInput) {
  EXPECT_THROW(make_central_composite_design({}, CcdOptions{}), InputError);
  EXPECT_THROW(make_central_composite_design({{"A", "", 0, 0}}, CcdOptions{}), InputError);  // step 0
  EXPECT_THROW(make_central_composite_design({{"A", "", 0, 1}, {"A", "", 0, 1}}, CcdOptions{}), InputError);
  CcdOptions negative_alpha;
  negative_alpha.alpha_kind = AlphaKind::given;
  negative_alpha.alpha = -1.0;
  EXPECT_THROW(make_central_composite_design(paper_factors, negative_alpha), InputError);
  EXPECT_THROW(make_central_composite_design(paper_factors, with_centre_points(-1)), InputError);
  // Finite centre and step whose sum overflows: the design had 'inf' in it.
  try {
    make_central_composite_design({{"A", "", 1e308, 1e308}, {"B", "", 1, 1}}, CcdOptions{});
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("factor 'A': its value at coded 1 is not a finite number"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace regodem::doe
