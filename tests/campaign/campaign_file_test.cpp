#include "tools/campaign/campaign_file.hpp"

#include <gtest/gtest.h>

#include <string>

#include "tests/campaign/campaign_fixture.hpp"

namespace tnv::campaign {
namespace {

CampaignResult parse(const std::string& text) { return parse_campaign_text(text, "study.toml", "."); }

TEST(CampaignFile, TheIssuesExampleIsRead) {
  const CampaignResult r = parse(test::example_campaign());
  ASSERT_TRUE(r.spec) << r.error;
  const CampaignSpec& s = *r.spec;
  EXPECT_EQ(s.experiment, "circle");
  ASSERT_EQ(s.controllers.size(), 1u);
  EXPECT_EQ(s.controllers[0], fw::ControllerKind::rdvsc);
  EXPECT_EQ(s.scenario, "no-cut");
  EXPECT_EQ(s.runs, 200u);
  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(s.sampling, Sampling::random);
  ASSERT_EQ(s.vary.size(), 3u);
  EXPECT_EQ(s.vary[0].name, "plant.x.coulomb_mm_s");
  EXPECT_FALSE(s.vary[0].is_parameter);
  EXPECT_EQ(s.vary[0].kind, DistributionKind::normal);
  EXPECT_EQ(s.vary[0].line, 7);
  EXPECT_FALSE(s.vary[1].is_parameter);
  EXPECT_TRUE(s.vary[2].is_parameter);  // a firmware parameter by its documented name
  EXPECT_DOUBLE_EQ(s.vary[2].a, 0.35);
  EXPECT_DOUBLE_EQ(s.vary[2].b, 0.45);
}

TEST(CampaignFile, ListsLognormalAndLatinHypercubeAreRead) {
  const CampaignResult r = parse(R"(experiment = "circle"
controllers = ["pid", "rdvsc"]
scenario = "cut-1200"
runs = 10
seed = 1
sampling = "latin-hypercube"
limit_um = 4.5
[vary]
"plant.x.backlash_um" = { lognormal = [2.0, 0.5] }
"x.controller" = { list = ["pid", "rdvsc"] }
"cutting.flutes" = { list = [2, 4] }
)");
  ASSERT_TRUE(r.spec) << r.error;
  EXPECT_EQ(r.spec->sampling, Sampling::latin_hypercube);
  EXPECT_DOUBLE_EQ(r.spec->limit_um, 4.5);
  EXPECT_EQ(r.spec->vary[0].kind, DistributionKind::lognormal);
  EXPECT_EQ(r.spec->vary[1].kind, DistributionKind::list);
  EXPECT_TRUE(r.spec->vary[1].is_parameter);
  EXPECT_EQ(r.spec->vary[2].values.size(), 2u);
  // The list is drawn by strata of the unit interval.
  EXPECT_EQ(value_at(r.spec->vary[2], 0.25), 2);
  EXPECT_EQ(value_at(r.spec->vary[2], 0.75), 4);
}

struct BadCase {
  const char* what;
  std::string text;
  const char* expected;  // the error must contain this
};

std::string with_vary(const std::string& vary) {
  return "experiment = \"circle\"\ncontrollers = [\"rdvsc\"]\nscenario = \"no-cut\"\nruns = 4\nseed = 1\n[vary]\n" + vary;
}

TEST(CampaignFile, BadFilesAreRefusedWithFileLineAndKey) {
  const BadCase cases[] = {
      {"unknown top-level key", "experiment = \"circle\"\nrunz = 4\n", "study.toml:2:1: runz: unknown key"},
      {"unknown experiment", "experiment = \"spiral\"\n", "study.toml:1:1: experiment: \"spiral\""},
      {"missing key", "experiment = \"circle\"\ncontrollers = [\"pid\"]\nscenario = \"no-cut\"\nseed = 1\n",
       "runs: required"},
      {"bad controller", "controllers = [\"pid\", \"lqr\"]\n", "study.toml:1:"},
      {"unknown scenario", "scenario = \"no-such\"\n", "study.toml:1:1: scenario: \"no-such\" is neither a built-in"},
      {"neither scenario key nor parameter", with_vary("\"plant.x.colomb_mm_s\" = { uniform = [1, 2] }\n"),
       "study.toml:7:1: vary.\"plant.x.colomb_mm_s\": neither a scenario key"},
      {"neither, no section", with_vary("\"x.sliding.gama\" = { uniform = [1, 2] }\n"),
       "study.toml:7:1: vary.\"x.sliding.gama\": neither a scenario key"},
      {"uniform outside a scenario key's range", with_vary("\"plant.y.gain\" = { uniform = [-0.5, 1.2] }\n"),
       "study.toml:7:1: vary.\"plant.y.gain\": uniform low end (-0.5) is outside the key's valid range: plant.y.gain"},
      {"uniform outside a parameter's range", with_vary("\"x.sliding.gamma\" = { uniform = [0.35, 45] }\n"),
       "study.toml:7:1: vary.\"x.sliding.gamma\": uniform high end (45) is outside the key's valid range"},
      {"normal mean outside", with_vary("\"plant.x.tau_s\" = { normal = [-1, 0.1] }\n"),
       "vary.\"plant.x.tau_s\": normal mean (-1) is outside"},
      {"list value outside", with_vary("\"x.controller\" = { list = [\"pid\", \"lqr\"] }\n"),
       "vary.\"x.controller\": list value \"lqr\""},
      {"sigma zero", with_vary("\"plant.x.tau_s\" = { normal = [0.1, 0] }\n"), "needs sigma > 0"},
      {"low above high", with_vary("\"plant.y.gain\" = { uniform = [1.2, 0.8] }\n"), "needs lo < hi"},
      {"unknown distribution", with_vary("\"plant.y.gain\" = { triangular = [1, 2] }\n"),
       "\"triangular\": not a distribution"},
      {"two distributions", with_vary("\"plant.y.gain\" = { uniform = [1, 2], normal = [1, 1] }\n"),
       "expected one distribution"},
      {"syntax", "experiment = \n", "study.toml:1:"},
  };
  for (const BadCase& c : cases) {
    const CampaignResult r = parse(c.text);
    EXPECT_FALSE(r.spec) << c.what;
    EXPECT_NE(r.error.find(c.expected), std::string::npos) << c.what << ": " << r.error;
  }
}

}  // namespace
}  // namespace tnv::campaign
