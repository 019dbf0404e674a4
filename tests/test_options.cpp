// The typed options (base/options.h): one declaration per member gives the descriptor,
// the checks and the filled struct, and turns a struct back into the options that read
// the same struct again (what a child process is given); the run options are one such table.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "base/options.h"
#include "harness/run_options.h"
#include "test_util.h"

namespace {

using sbtest::expectInputError;

enum class Mode { Fast, Exact };

struct Inner {
  bool sah = true;
};

struct Settings {
  int layers = 0;
  float bias = 0;
  Mode mode = Mode::Fast;
  std::string kind;
  bool jitter = false;
  std::string note;
  Inner inner;
};

const sb::OptionTable<Settings>& table() {
  using S = Settings;
  static const sb::OptionTable<S> t(
      {sb::opt::integer(&S::layers, "layers", 3, 1, 8, "layers, 1..8"),
       sb::opt::number(&S::bias, "bias", "0.002", 0, 1, "bias, 0..1"),
       sb::opt::choice(&S::mode, "mode", "fast", {{"fast", Mode::Fast}, {"exact", Mode::Exact}},
                       "fast | exact"),
       sb::opt::choice(&S::kind, "kind", "power", {"power", "trig", "log"}, "power | trig | log"),
       sb::opt::flag(&S::jitter, "jitter", false, "on | off"),
       sb::opt::text(&S::note, "note", "", "any text"),
       sb::opt::nested(&S::inner, sb::opt::group<Inner>({sb::opt::choice(
                                      &Inner::sah, "bvh", "sah", {{"sah", true}, {"median", false}},
                                      "sah | median")}))},
      [](S& s) {
        if (s.mode == Mode::Exact && s.layers > 4)
          throw sb::InputError("thing: mode=exact takes at most 4 layers");
      });
  return t;
}

Settings read(const std::string& spec) { return table().read(sb::Spec::parse(spec), "thing"); }

TEST(Options, DeclarationsGiveTheDescriptor) {
  const std::vector<sb::OptionInfo> infos = table().infos();
  ASSERT_EQ(infos.size(), 7u);
  EXPECT_EQ(infos[0].name, "layers");
  EXPECT_EQ(infos[0].kind, sb::OptionKind::Integer);
  EXPECT_EQ(infos[0].defaultValue, "3");
  EXPECT_EQ(infos[0].max, 8);
  EXPECT_EQ(infos[2].choices, (std::vector<std::string>{"fast", "exact"}));
  EXPECT_EQ(infos[4].kind, sb::OptionKind::Flag);
  EXPECT_EQ(infos[6].name, "bvh");  // a nested part's options follow in order
}

TEST(Options, DefaultsAndGivenValuesFillTheMembers) {
  const Settings d = read("thing");
  EXPECT_EQ(d.layers, 3);
  EXPECT_FLOAT_EQ(d.bias, 0.002f);
  EXPECT_EQ(d.mode, Mode::Fast);
  EXPECT_EQ(d.kind, "power");
  EXPECT_FALSE(d.jitter);
  EXPECT_TRUE(d.inner.sah);
  const Settings s = read("thing:layers=4,bias=0.5,mode=exact,kind=trig,jitter=on,bvh=median");
  EXPECT_EQ(s.layers, 4);
  EXPECT_FLOAT_EQ(s.bias, 0.5f);
  EXPECT_EQ(s.mode, Mode::Exact);
  EXPECT_EQ(s.kind, "trig");
  EXPECT_TRUE(s.jitter);
  EXPECT_FALSE(s.inner.sah);
}

TEST(Options, BadValuesAreRefusedWithTheSameMessages) {
  expectInputError([] { read("thing:layer=2"); },
                   {"unknown option 'layer' for thing", "did you mean 'layers'?"});
  expectInputError([] { read("thing:layers=9"); },
                   {"thing: option layers=9 is out of range [1, 8]"});
  expectInputError([] { read("thing:bias=x"); }, {"option bias=x is not a finite number"});
  expectInputError([] { read("thing:mode=exakt"); },
                   {"option mode=exakt is not one of fast exact", "did you mean 'exact'?"});
  expectInputError([] { read("thing:jitter=yes"); }, {"option jitter=yes is not one of on off"});
  // The rule between options (finish).
  expectInputError([] { read("thing:mode=exact,layers=5"); }, {"at most 4 layers"});
  EXPECT_NO_THROW(read("thing:mode=exact,layers=4"));
}

TEST(Options, GivenReadsBackTheSameStruct) {
  EXPECT_TRUE(table().given(read("thing")).empty());
  const Settings s = read("thing:layers=4,bias=0.25,mode=exact,jitter=on,note=a b,bvh=median");
  sb::Spec spec{"thing", {}};
  for (const auto& [name, text] : table().given(s)) spec.options[name] = text;
  EXPECT_EQ(spec.str(), "thing:bias=0.25,bvh=median,jitter=on,layers=4,mode=exact,note=a b");
  const Settings again = table().read(spec, "thing");
  EXPECT_EQ(again.layers, s.layers);
  EXPECT_EQ(again.bias, s.bias);
  EXPECT_EQ(again.mode, s.mode);
  EXPECT_EQ(again.jitter, s.jitter);
  EXPECT_EQ(again.note, s.note);
  EXPECT_EQ(again.inner.sah, s.inner.sah);
}

TEST(Options, RunOptionsBecomeAChildsArguments) {
  EXPECT_TRUE(sb::runOptionArguments({}).empty());
  const sb::RunOptions o{3, 6, 2.5};
  EXPECT_EQ(sb::runOptionArguments(o),
            (std::vector<std::string>{"--min-reps", "3", "--max-reps", "6", "--target-ci", "2.5"}));
  sb::Spec spec;
  spec.options = {{"min-reps", "3"}, {"max-reps", "6"}, {"target-ci", "2.5"}};
  const sb::RunOptions back = sb::runOptionTable().read(spec, "run options");
  EXPECT_EQ(back.minReps, 3);
  EXPECT_EQ(back.maxReps, 6);
  EXPECT_EQ(back.targetCiPct, 2.5);
  spec.options = {{"min-reps", "3"}, {"max-reps", "2"}};
  expectInputError([&] { sb::runOptionTable().read(spec, "run options"); },
                   {"--max-reps 2: below --min-reps 3"});
  spec.options = {{"target-ci", "101"}};
  expectInputError([&] { sb::runOptionTable().read(spec, "run options"); },
                   {"target-ci=101 is out of range [0.000000, 100.000000]"});
  // Defaults resolved: the command's rounds, 15 at most with a target.
  const sb::RepetitionOptions r = sb::repetitions({0, 0, 5}, 4);
  EXPECT_EQ(r.minReps, 4);
  EXPECT_EQ(r.maxReps, 15);
  EXPECT_EQ(sb::repetitions({0, 2, 0}, 4).minReps, 2);
}

}  // namespace
