// Random campaigns without GL: the generators' determinism and validity, failure classes,
// shrinking on a planted fault (a renderer that draws the exact reference and plants NaN where
// a triangle has a vertex with w_c < 1), and a whole campaign on that fault.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "campaign/campaign.hpp"
#include "campaign/failure.hpp"
#include "campaign/generators.hpp"
#include "campaign/random.hpp"
#include "campaign/shrink.hpp"
#include "casefile/casefile.hpp"
#include "casefile/write.hpp"
#include "check/check.hpp"

namespace {

using namespace glrc;
using namespace glrc::campaign;

std::vector<const Generator*> all_generators() {
  std::vector<const Generator*> out;
  for (const Generator& g : generators())
    out.push_back(&g);
  return out;
}

std::vector<const Generator*> only(std::string_view name) {
  const Generator* g = find_generator(name);
  EXPECT_NE(g, nullptr) << name;
  return {g};
}

TEST(Random, IsSplitMix64) {
  // The first outputs of SplitMix64 seeded with 42, from an independent implementation.
  Random r(42);
  EXPECT_EQ(r.next(), 13679457532755275413ull);
  EXPECT_EQ(r.next(), 2949826092126892291ull);
  EXPECT_EQ(r.next(), 5139283748462763858ull);
  Random again(42);
  EXPECT_EQ(again.below(1000), 741u);  // the high 64 bits of 13679457532755275413 * 1000
  for (int k = 0; k < 1000; ++k) {
    const int v = again.between(-3, 3);
    EXPECT_GE(v, -3);
    EXPECT_LE(v, 3);
    const double b = again.binades(-2, 1);
    EXPECT_GE(b, 0.25);
    EXPECT_LT(b, 4.0);
  }
}

TEST(Generators, EveryNameIsFoundAndNothingElse) {
  EXPECT_EQ(generators().size(), 6u);
  for (const char* name : {"sizes", "clip", "mesh", "attributes", "states", "dense"})
    EXPECT_NE(find_generator(name), nullptr) << name;
  EXPECT_EQ(find_generator("Clip"), nullptr);
  EXPECT_EQ(find_generator(""), nullptr);
}

TEST(Generators, TheSameSeedAndIndexGiveTheSameCaseAndEveryCaseLoads) {
  const auto chosen = all_generators();
  std::set<std::string> texts;
  for (uint64_t index = 0; index < 150; ++index) {
    const Case a = generate(chosen, 7, index);
    const Case b = generate(chosen, 7, index);
    const std::string text = casefile::to_case_file(a);
    ASSERT_EQ(text, casefile::to_case_file(b)) << a.name;
    texts.insert(text);
    EXPECT_EQ(a.name, "fuzz_" + std::string(generator_for(chosen, index).name) + "_7_" +
                          std::to_string(index));
    EXPECT_FALSE(a.triangles.empty()) << a.name;
    // The loader takes it as it is: the same bits back.
    Case loaded;
    ASSERT_NO_THROW(loaded = casefile::parse(text, a.name, a.name)) << text.substr(0, 400);
    EXPECT_EQ(casefile::to_case_file(loaded), text) << a.name;
    // A generator's case does not depend on which others the campaign has.
    const Case alone = generate({&generator_for(chosen, index)}, 7, index);
    EXPECT_EQ(casefile::to_case_file(alone), text) << a.name;
  }
  EXPECT_EQ(texts.size(), 150u) << "two indices gave the same case";
  EXPECT_NE(casefile::to_case_file(generate(chosen, 8, 0)),
            casefile::to_case_file(generate(chosen, 7, 0)));
}

TEST(Generators, AimWhereTheySay) {
  // Over 60 cases each: clip puts vertices on the planes and behind the eye; mesh shares
  // vertices between triangles; attributes spans 1e-30 to 1e30; sizes makes long framebuffers.
  int on_plane = 0, behind = 0, shared = 0, tiny = 0, huge = 0, long_framebuffer = 0;
  for (uint64_t index = 0; index < 60; ++index) {
    const Case clip = generate(only("clip"), 3, index);
    for (const Vertex& v : clip.vertices) {
      on_plane += std::fabs(v.clip[0]) == std::fabs(v.clip[3]) && v.clip[3] != 0;
      behind += v.clip[3] <= 0;
    }
    const Case mesh = generate(only("mesh"), 3, index);
    shared += mesh.vertices.size() < 3 * mesh.triangles.size();
    const Case attributes = generate(only("attributes"), 3, index);
    for (const Vertex& v : attributes.vertices)
      for (const float x : v.values) {
        tiny += x != 0 && std::fabs(x) < 1e-25f;
        huge += std::fabs(x) > 1e25f;
      }
    const Case sizes = generate(only("sizes"), 3, index);
    long_framebuffer += std::max(sizes.fb_width, sizes.fb_height) >= 1024;
  }
  EXPECT_GT(on_plane, 20);
  EXPECT_GT(behind, 20);
  EXPECT_EQ(shared, 60);
  EXPECT_GT(tiny, 10);
  EXPECT_GT(huge, 10);
  EXPECT_GT(long_framebuffer, 3);
}

TEST(Failures, ClassesComeInPrecedenceOrderWithTheChannelsKind) {
  Case c;
  c.varyings = {{"a", 2, Interpolation::noperspective}, {"b", 1, Interpolation::flat}};
  CaseResult r;
  r.outcome = Status::fail;
  r.channels.resize(4);
  r.channels[0].name = "depth";
  r.channels[1].name = "a.x";
  r.channels[2].name = "a.y";
  r.channels[3].name = "b";
  r.channels[2].non_finite = 3, r.channels[2].over_tolerance = 5;
  r.channels[0].over_tolerance = 1;
  r.coverage.gaps = 2;
  const std::vector<Failure> f = failures_of(c, r);
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0].signature(), "non_finite/noperspective");
  EXPECT_EQ(f[1].signature(), "gap");
  EXPECT_EQ(f[2].signature(), "value/depth");
  EXPECT_EQ(f[3].signature(), "value/noperspective");
  r.outcome = Status::crash;
  EXPECT_EQ(failures_of(c, r).front().signature(), "crash");
  r.outcome = Status::skip;  // beyond GL's specified range: not judged
  EXPECT_TRUE(failures_of(c, r).empty());
  r.outcome = Status::pass;
  EXPECT_TRUE(failures_of(c, r).empty());
  EXPECT_EQ(failure_file_name(f[0]), "non_finite_noperspective.json");
}

TEST(Shrink, SimplerNumbersComeFirst) {
  EXPECT_EQ(complexity(0.0f), 0);
  EXPECT_LT(complexity(0.0f), complexity(-0.0f));
  EXPECT_LT(complexity(-0.0f), complexity(1.0f));
  EXPECT_LT(complexity(1.0f), complexity(-1.0f));
  EXPECT_LT(complexity(1.0f), complexity(3.0f));
  EXPECT_LT(complexity(3.0f), complexity(0.5f));   // integers before fractions
  EXPECT_LT(complexity(0.5f), complexity(0.75f));  // fewer mantissa bits
  EXPECT_LT(complexity(0.75f), complexity(0.1f));
  EXPECT_LT(complexity(16.0f), complexity(17.0f));
  EXPECT_LT(complexity(0x1p-3f), complexity(0x1p-60f));  // smaller exponents
}

// "GL": the exact reference's own frame, with NaN planted in the first component wherever the
// covering triangle has a vertex with 0 < w_c < 1 and that component is smooth.
class PlantedFault : public gl::Renderer {
 public:
  PlantedFault() { info_.renderer = "planted fault (test)", info_.subpixel_bits = 8; }
  const gl::GlInfo& info() const override { return info_; }
  Frame render(const Case& c) override {
    Frame f = check::expectation_for(c, check::CheckOptions{}, 8).frame;
    if (c.varyings.empty() || c.varyings[0].interpolation != Interpolation::smooth) return f;
    for (size_t p = 0; p < f.pixel_count(); ++p) {
      const int32_t t = f.primitive[p];
      if (t < 0) continue;
      bool near = false;
      for (const uint32_t v : c.triangles[size_t(t)])
        near = near || (c.vertices[v].clip[3] > 0 && c.vertices[v].clip[3] < 1);
      if (near) f.components[0][p] = NAN;
    }
    return f;
  }

 private:
  gl::GlInfo info_;
};

Judge planted_judge(int* checks = nullptr) {
  return [checks](const std::vector<Case>& cases) {
    PlantedFault gl;
    std::vector<CaseResult> out;
    for (const Case& c : cases)
      out.push_back(check::check(c, gl, check::CheckOptions{}));
    if (checks) *checks += int(cases.size());
    return out;
  };
}

// The first case of the states generator (seed 11) that the planted fault fails.
std::pair<Case, CaseResult> first_planted_failure() {
  const Judge judge = planted_judge();
  for (uint64_t index = 0; index < 200; ++index) {
    Case c = generate(only("states"), 11, index);
    c.varyings[0].interpolation = Interpolation::smooth;  // the flat vec2 becomes smooth
    const CaseResult r = judge({c}).front();
    if (!failures_of(c, r).empty()) return {c, r};
  }
  ADD_FAILURE() << "no case of 200 fails the planted fault";
  return {};
}

TEST(Shrink, APlantedFaultShrinksToAKnownMinimalCase) {
  const auto [failing, result] = first_planted_failure();
  const std::vector<Failure> f = failures_of(failing, result);
  ASSERT_FALSE(f.empty());
  ASSERT_EQ(f.front().signature(), "non_finite/smooth");
  ASSERT_GT(failing.triangles.size(), 1u);

  int checks = 0;
  const Shrunk s = shrink(failing, result, f.front(), planted_judge(&checks));
  EXPECT_TRUE(s.complete);
  EXPECT_EQ(s.checks, checks);
  const Case& m = s.minimal;
  // The fault needs one triangle with a vertex at 0 < w_c < 1 and one smooth component: nothing
  // else is left, in a framebuffer of one pixel.
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.vertices.size(), 3u);
  ASSERT_EQ(m.varyings.size(), 1u);
  EXPECT_EQ(m.varyings[0].size, 1);
  EXPECT_EQ(m.varyings[0].interpolation, Interpolation::smooth);
  EXPECT_EQ(m.fb_width, 1);
  EXPECT_EQ(m.fb_height, 1);
  // Known: two vertices at infinity (w_c = 0) and the pixel centre's vertex at w_c = 0.25, every
  // value 0, every state GL's default. 0.25 stays: w_c = 1 would end the fault and no simpler
  // number than 0.25 that shrinking tries (0, 1, the nearest integer, fewer mantissa bits) keeps
  // it.
  const std::string text = casefile::to_case_file(m);
  EXPECT_EQ(text.substr(text.find("\"framebuffer\"")),
            std::string(R"("framebuffer": {"width": 1, "height": 1},
  "viewport": {"x": 0, "y": 0, "width": 1, "height": 1},
  "varyings": [
    {"name": "v1", "size": 1, "interpolation": "smooth"}
  ],
  "vertices": [
    {"clip": [1, 0, 0, 0], "v1": 0},
    {"clip": [0, 1, 0, 0], "v1": 0},
    {"clip": [0, 0, 0, 0.25], "v1": 0}
  ],
  "triangles": [
    [0, 1, 2]
  ]
}
)"));
  EXPECT_TRUE(shows(m, s.result, f.front()));
  // The same input shrinks to the same case.
  const Shrunk again = shrink(failing, result, f.front(), planted_judge());
  EXPECT_EQ(casefile::to_case_file(again.minimal), casefile::to_case_file(m));
}

TEST(Shrink, StopsAtItsBudgetWithTheSmallestCaseSoFar) {
  const auto [failing, result] = first_planted_failure();
  const Failure target = failures_of(failing, result).front();
  ShrinkOptions o;
  o.max_checks = 3;
  o.batch = 1;
  const Shrunk s = shrink(failing, result, target, planted_judge(), o);
  EXPECT_FALSE(s.complete);
  EXPECT_LE(s.checks, 3);
  EXPECT_TRUE(shows(s.minimal, s.result, target));
  EXPECT_LE(s.minimal.triangles.size(), failing.triangles.size());
}

TEST(Campaign, FindsThePlantedFaultOnceAndCountsWhatItChecked) {
  CampaignOptions o;
  o.seed = 5;
  o.count = 30;
  o.generators = only("states");
  o.batch = 7;
  int batches = 0;
  CampaignProgress progress;
  progress.batch_done = [&](const CampaignStats&, size_t) { ++batches; };
  // The states generator's first varying is flat: the fault needs a smooth one, which the
  // attributes generator makes too.
  o.generators = all_generators();
  const CampaignResult r = run_campaign(o, planted_judge(), progress);
  EXPECT_EQ(r.stats.cases, 30u);
  EXPECT_EQ(batches, 5);  // 7 + 7 + 7 + 7 + 2
  EXPECT_GT(r.stats.triangles, 30u);
  EXPECT_GT(r.stats.pixels, 1000u);
  ASSERT_GE(r.failures.size(), 1u);
  const FoundFailure* planted = nullptr;
  for (const FoundFailure& f : r.failures) {
    EXPECT_EQ(f.failure.kind, FailureClass::non_finite) << f.failure.signature();
    if (f.failure.signature() == "non_finite/smooth") planted = &f;
  }
  ASSERT_NE(planted, nullptr);
  EXPECT_EQ(planted->minimal.triangles.size(), 1u);
  EXPECT_EQ(planted->minimal.name, "non_finite_smooth");
  EXPECT_GE(planted->cases, 1u);
  EXPECT_EQ(planted->examples.front(), planted->index);
  // The minimal case is a case file the loader takes.
  EXPECT_NO_THROW(casefile::parse(casefile::to_case_file(planted->minimal), "m", "m"));

  // Two shards check the campaign's cases between them, each once.
  std::multiset<uint64_t> indices;
  for (int start = 1; start <= 2; ++start) {
    CampaignOptions shard = o;
    shard.fraction = 2, shard.fraction_start = start, shard.shrink = false;
    const CampaignResult s = run_campaign(shard, planted_judge());
    EXPECT_EQ(s.stats.cases, 15u);
    for (const FoundFailure& f : s.failures)
      for (const uint64_t k : f.examples)
        EXPECT_EQ(int(k % 2), start - 1);
  }
}

// Skipped cases are kept with their reasons: the first kSkippedExamples by index, as the
// campaign's results.json lists them, and the merge of shards lists the unsharded campaign's.
TEST(Campaign, KeepsTheFirstSkippedCasesWithTheirReasons) {
  // A judge that skips every third case, saying which.
  const Judge skipping = [](const std::vector<Case>& cases) {
    std::vector<CaseResult> out;
    for (const Case& c : cases) {
      CaseResult r;
      r.name = c.name;
      const bool skip = std::stoull(c.name.substr(c.name.rfind('_') + 1)) % 3 == 0;
      r.status = r.outcome = skip ? Status::skip : Status::pass;
      if (skip) r.message = "outside GL's specified range: " + c.name;
      out.push_back(r);
    }
    return out;
  };
  CampaignOptions o;
  o.seed = 4;
  o.count = 60;
  o.generators = only("states");
  o.batch = 8;
  const CampaignResult whole = run_campaign(o, skipping);
  EXPECT_EQ(whole.stats.skipped, 20u);
  ASSERT_EQ(whole.skipped.size(), kSkippedExamples);
  for (size_t k = 0; k < whole.skipped.size(); ++k) {
    EXPECT_EQ(whole.skipped[k].index, 3 * k);
    EXPECT_EQ(whole.skipped[k].generator, "states");
    EXPECT_EQ(whole.skipped[k].message,
              "outside GL's specified range: fuzz_states_4_" + std::to_string(3 * k));
  }
  const nlohmann::json json = campaign_json(whole, nlohmann::json::object());
  EXPECT_EQ(json["skipped"][1]["replay"], "glrefcheck fuzz --generator states --replay 4:3");

  std::vector<nlohmann::json> shards;
  std::vector<std::string> sources;
  for (int start = 1; start <= 2; ++start) {
    CampaignOptions shard = o;
    shard.fraction = 2, shard.fraction_start = start;
    // As `merge` reads them: from their files.
    shards.push_back(nlohmann::json::parse(
        campaign_json(run_campaign(shard, skipping), nlohmann::json::object()).dump()));
    sources.push_back("shard" + std::to_string(start));
  }
  std::vector<size_t> from;
  EXPECT_EQ(merge_campaigns(shards, sources, from)["skipped"], json["skipped"]);
}

}  // namespace
