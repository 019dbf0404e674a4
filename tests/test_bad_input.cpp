// Bad input, one test per kind the issue lists, each through every command that
// takes it (render, probe, check, bless, compare, bench-*, list): exit status 2,
// a message on stderr that names the thing and the problem (and the closest
// valid name where there is one), nothing on stdout, and nothing written: each
// command runs in a fresh folder that holds all its inputs and outputs, and the
// folder must be byte-identical afterwards (no output, no temporary file).
//
// Tests elsewhere that cover parts of this list:
//   Cli/CliBadInput.ClearMessageExit2NothingWritten/* (tests/test_cli.cpp): one render
//     flag or spec each (unknown scene, option, technique, backend, platform and
//     flag; strands=-1, size=0, --size 0x0, --repeat 0; /nonexistent-dir/x.png);
//   CliBadFiles.TruncatedAndCorruptFilesExit2 (tests/test_cli.cpp): malformed strand files;
//   Check.MalformedManifestExits2NamingTheFile (tests/test_check.cpp): manifest errors;
//   Check.MissingBaselineIsReported (tests/test_check.cpp): a case's baseline image
//     missing is a check result, not bad input: MISSING and exit status 1 (README);
//   Registry.ValidatesTechniqueNamesAndOptions (tests/test_techniques.cpp): the same
//     names and ranges without the CLI.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using sbtest::CliResult;
using sbtest::readFile;

const std::string kScene = "straight:strands=40,points=6,seed=3";
const fs::path kCommitted = fs::path(SB_SOURCE_DIR) / "baselines";
const std::string kCommittedCase =
    "--baselines " + kCommitted.string() + " --filter '^straight-lines-none$'";  // gl and vulkan

// Environments without a device (each variable names a file that does not exist).
const std::string kNoVulkan =
    "VK_ICD_FILENAMES=/nonexistent.json VK_DRIVER_FILES=/nonexistent.json";
const std::string kNoEgl = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json";  // glvnd: no vendor
const std::string kNoGl45 = "MESA_GL_VERSION_OVERRIDE=3.3";  // EGL and OSMesa: no 4.5 context

// Every entry under dir, recursively: relative path -> bytes ("/" for a folder).
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> m;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    m[fs::relative(e.path(), dir).string()] = e.is_directory() ? "/" : readFile(e.path());
  return m;
}

// A folder holding a command's inputs; every command runs inside it, so that a
// default relative output path would land there too.
struct Sandbox {
  fs::path dir = sbtest::tempDir("bad-input");
  std::map<std::string, std::string> inputs;

  Sandbox() {
    std::ofstream(dir / "file") << "a regular file, not a folder\n";
    fs::create_directories(dir / "empty");
    freeze();
  }
  ~Sandbox() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  // Call after adding inputs: what the folder must hold after each rejected command.
  void freeze() { inputs = snapshot(dir); }

  // "{dir}" in args stands for the sandbox folder; env: "NAME=value ..." or "".
  CliResult run(std::string args, const std::string& env = "") const {
    for (std::size_t p; (p = args.find("{dir}")) != std::string::npos;)
      args.replace(p, 5, dir.string());
    const fs::path io = sbtest::tempDir("bad-input-io");
    const std::string cmd = "cd '" + dir.string() + "' && env " + env + " " + SB_CLI + " " + args +
                            " >" + (io / "out").string() + " 2>" + (io / "err").string();
    CliResult r;
    const int raw = std::system(cmd.c_str());
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = readFile(io / "out");
    r.err = readFile(io / "err");
    fs::remove_all(io);
    return r;
  }

  // Exit status 2, every needle in the message, nothing printed on stdout,
  // nothing written or left behind.
  void expectRejected(const std::string& args, std::vector<std::string> needles,
                      const std::string& env = "") const {
    SCOPED_TRACE((env.empty() ? "" : env + " ") + "strandbench " + args);
    const CliResult r = run(args, env);
    EXPECT_EQ(r.status, 2) << r.err;
    for (std::string& n : needles) {
      for (std::size_t p; (p = n.find("{dir}")) != std::string::npos;)
        n.replace(p, 5, dir.string());
      EXPECT_NE(r.err.find(n), std::string::npos) << "stderr lacks '" << n << "':\n" << r.err;
    }
    EXPECT_EQ(r.out, "") << "printed before failing";
    EXPECT_EQ(snapshot(dir), inputs) << "wrote or left files behind";
  }

  // A baselines folder {dir}/baselines whose manifest holds `cases` (16x16, gl only).
  void writeManifest(const nlohmann::json& cases) {
    fs::create_directories(dir / "baselines");
    const nlohmann::json m = {
        {"format", 1},
        {"tolerances",
         {{"t",
           {{"max_abs", 0.01},
            {"max_failing_fraction", 0.001},
            {"failing_threshold", 0.001},
            {"min_psnr", 60}}}}},
        {"defaults", {{"size", "16x16"}, {"tolerance", "t"}, {"backends", {"gl"}}}},
        {"cases", cases}};
    std::ofstream(dir / "baselines" / "manifest.json") << m.dump(2) << "\n";
    freeze();
  }
};

const std::string kCheck = "check --baselines {dir}/baselines --out {dir}/out";
const std::string kBless = "bless --baselines {dir}/baselines";

// ------------------------------------------------------------------ names

TEST(BadInput, UnknownNamesGetTheClosestValidName) {
  Sandbox s;
  const std::string render = "render --size 16x16 --out {dir}/x.png ";
  // `word` misspelt where `command` has {}: "unknown <what> '<word>'" and the closest name.
  auto typo = [&](std::string command, const std::string& what, const std::string& word,
                  const std::string& closest) {
    command.replace(command.find("{}"), 2, word);
    s.expectRejected(command,
                     {"unknown " + what + " '" + word + "'", "did you mean '" + closest + "'"});
  };
  typo(render + "--scene {}", "scene", "curli", "curly");
  typo(render + "--shadow {}", "shadow technique", "shadowmapp", "shadowmap");
  typo(render + "--oit {}", "transparency technique", "wbiot", "wboit");
  s.expectRejected(render + "--scene straight:strandz=5",
                   {"unknown option 'strandz' for scene 'straight'", "did you mean 'strands'"});
  s.expectRejected(render + "--shadow dom:layres=3",
                   {"unknown option 'layres' for shadow technique 'dom'", "did you mean 'layers'"});
  typo(render + "--oit occupancy:{}=64", "option", "slises", "slices");
  s.expectRejected(render + "--backend vulcan",
                   {"--backend vulcan", "unknown backend 'vulcan'", "did you mean 'vulkan'"});
  typo(render + "--platform {}", "gl platform", "osmsa", "osmesa");
  typo(render + "{} egl", "render option", "--platfrom", "--platform");
  typo("probe --shadow {} --out {dir}/p.csv", "shadow technique", "ocupancy", "occupancy");
  typo("probe {} 1,1 --out {dir}/p.csv", "probe option", "--texl", "--texel");
  typo("compare {dir}/a.png {dir}/b.png {} {dir}/h.png", "compare option", "--heatmpa",
       "--heatmap");
  typo("bench-shadows --scene {} --size 16x16 --repeat 1", "scene", "curli", "curly");
  typo("bench-oit --scene " + kScene + " --shadow {} --size 16x16", "shadow technique",
       "shadowmapp", "shadowmap");
  typo("list {}", "list option", "--jsn", "--json");
  typo(kCheck + " {} x", "check option", "--filtr", "--filter");
  // A manifest case: the message names the manifest and the case. The valid
  // first case is not rendered either (nothing printed, no out folder).
  s.writeManifest(
      {{{"name", "fine"}, {"scene", kScene}}, {{"name", "typo"}, {"scene", "curli:strands=10"}}});
  for (const std::string& cmd : {kCheck, kBless})
    s.expectRejected(cmd, {"{dir}/baselines/manifest.json", "case 'typo'", "did you mean 'curly'"});
  s.writeManifest({{{"name", "typo2"}, {"scene", kScene}, {"oit", "pel"}}});
  s.expectRejected(kCheck, {"case 'typo2'", "unknown transparency technique 'pel'", "'peel'"});
}

// A mistyped command gets the closest one, as a mistyped option does; no command
// at all prints the usage (the commands and what they do).
TEST(BadInput, UnknownOrMissingCommand) {
  Sandbox s;
  s.expectRejected("rendr --size 16x16", {"unknown command 'rendr'", "did you mean 'render'"});
  s.expectRejected("chek", {"unknown command 'chek'", "did you mean 'check'"});
  s.expectRejected("", {"give a command", "Usage:", "render", "check", "view"});
}

// A flag given twice is named, with both values, in words (not CLI11's "At Most 1
// required but received 2").
TEST(BadInput, RepeatedFlagIsNamed) {
  Sandbox s;
  s.expectRejected("render --scene " + kScene + " --size 16x16 --size 32x32 --out {dir}/x.png",
                   {"render: --size given 2 times (16x16, 32x32): give it once"});
  s.expectRejected("compare {dir}/a.png {dir}/b.png --ppd 40 --ppd 60",
                   {"compare: --ppd given 2 times (40, 60): give it once"});
  s.expectRejected(kCheck + " --filter a --filter b --filter c", {"--filter given 3 times"});
}

// ------------------------------------------------------------------ values

TEST(BadInput, OutOfRangeValues) {
  Sandbox s;
  const std::string render = "render --scene " + kScene + " --size 16x16 --out {dir}/x.png ";
  s.expectRejected(render + "--shadow dom:layers=0",
                   {"shadow technique 'dom'", "layers=0", "out of range [1, 31]"});
  // `strandbench list`: both occupancy techniques take `slices`, a multiple of 32.
  s.expectRejected(render + "--shadow occupancy:slices=33",
                   {"shadow technique 'occupancy'", "slices=33", "multiple of 32"});
  s.expectRejected(render + "--oit occupancy:slices=48",
                   {"transparency technique 'occupancy'", "slices=48", "multiple of 32"});
  s.expectRejected(render + "--shadow occupancy:slices=0", {"slices=0", "out of range"});
  s.expectRejected("render --scene straight:strands=-5 --out {dir}/x.png",
                   {"scene 'straight'", "strands=-5", "out of range"});
  s.expectRejected("render --scene curly:points=-1 --out {dir}/x.png",
                   {"scene 'curly'", "points=-1", "out of range"});
  s.expectRejected(render + "--shadow osm:maps=-3",
                   {"shadow technique 'osm'", "maps=-3", "out of range [1, 512]"});
  s.expectRejected("render --size 0x0 --out {dir}/x.png", {"--size 0x0", "1..16384"});
  s.expectRejected(render + "--warmup -1", {"--warmup", "at least 0"});
  s.expectRejected("compare {dir}/a.png {dir}/b.png --ppd 0", {"--ppd", "positive"});
  s.expectRejected("compare {dir}/a.png {dir}/b.png --ppd 1e9", {"--ppd", "at most 1000"});
  s.expectRejected("probe --samples -1 --out {dir}/p.csv", {"--samples", "2..1000000"});
  s.expectRejected("probe --map-size 0 --out {dir}/p.csv", {"--map-size 0", "1..16384"});
  s.expectRejected("probe --map-size -1 --out {dir}/p.csv", {"--map-size -1", "1..16384"});
  s.expectRejected("probe --shadow dom:layers=0 --out {dir}/p.csv", {"dom", "layers=0"});
  const std::string bench = " --scene " + kScene + " --size 16x16 --repeat 1";
  s.expectRejected("bench-shadows" + bench + " --osm-maps 1 -3", {"--osm-maps -3", "1..512"});
  s.expectRejected("bench-shadows --size 0x0", {"--size 0x0"});
  s.expectRejected("bench-oit --scene " + kScene + " --repeat 0", {"--repeat", "at least 1"});
  s.expectRejected("bench-oit --scene straight:strands=-5", {"strands=-5", "out of range"});
  s.writeManifest({{{"name", "zero-size"}, {"scene", kScene}, {"size", "0x0"}}});
  s.expectRejected(kCheck, {"{dir}/baselines/manifest.json", "zero-size", "\"size\" '0x0'"});
  s.writeManifest({{{"name", "fine"}, {"scene", kScene}},
                   {{"name", "no-layers"}, {"scene", kScene}, {"shadow", "dom:layers=0"}}});
  for (const std::string& cmd : {kCheck, kBless})
    s.expectRejected(cmd, {"{dir}/baselines/manifest.json", "case 'no-layers'", "layers=0"});
}

// ------------------------------------------------------------------ output folders

// Tests run as root, for whom permission bits do not stop writes: a path under
// a regular file and /proc stand for folders that cannot be written.
TEST(BadInput, UnwritableOutputFolder) {
  Sandbox s;
  fs::create_directories(s.dir / "folder.png");
  s.freeze();
  const std::string render = "render --scene " + kScene + " --size 16x16 ";
  s.expectRejected(render + "--out /nonexistent/dir/x.png",
                   {"--out /nonexistent/dir/x.png", "folder /nonexistent/dir does not exist"});
  s.expectRejected(render + "--out {dir}/file/x.png",
                   {"--out {dir}/file/x.png", "{dir}/file is a file, not a folder"});
  s.expectRejected(render + "--out /proc/x.png", {"--out /proc/x.png", "/proc is not writable"});
  s.expectRejected(render + "--out {dir}/folder.png", {"--out {dir}/folder.png", "is a folder"});
  s.expectRejected(render + "--reference --reference-out {dir}/file/r.png",
                   {"--reference-out {dir}/file/r.png", "not a folder"});
  s.expectRejected(render + "--reference --heatmap /proc/h.png",
                   {"--heatmap /proc/h.png", "not writable"});
  s.expectRejected("probe --scene stray:strands=50 --out {dir}/file/p.csv",
                   {"--out {dir}/file/p.csv", "{dir}/file is a file, not a folder"});
  s.expectRejected("probe --scene stray:strands=50 --out /proc/p.csv",
                   {"--out /proc/p.csv", "/proc is not writable"});
  s.expectRejected("compare {dir}/a.png {dir}/b.png --heatmap {dir}/file/h.png",
                   {"--heatmap {dir}/file/h.png", "not a folder"});
  s.expectRejected("compare {dir}/a.png {dir}/b.png --flip-map {dir}/file/f.png",
                   {"--flip-map {dir}/file/f.png", "not a folder"});
  s.expectRejected(render + "--flip-map {dir}/f.png", {"--flip-map need --reference"});
  // check writes failures to --out (made when first needed): refused up front,
  // even when every comparison would pass.
  s.expectRejected("check " + kCommittedCase + " --out {dir}/file/out",
                   {"--out {dir}/file/out", "{dir}/file is a file, not a folder"});
  s.expectRejected("check " + kCommittedCase + " --out /proc/check",
                   {"--out /proc/check", "/proc is not writable"});
  // bless writes only into its baselines folder: see MissingBaselines.
}

// ------------------------------------------------------------------ baselines

TEST(BadInput, MissingBaselines) {
  Sandbox s;
  for (const std::string cmd : {"check --out {dir}/out", "bless"}) {
    s.expectRejected(cmd + " --baselines /nonexistent/baselines",
                     {"--baselines /nonexistent/baselines", "no such baselines folder"});
    s.expectRejected(cmd + " --baselines {dir}/file", {"--baselines {dir}/file", "is a file"});
    s.expectRejected(cmd + " --baselines {dir}/empty",
                     {"{dir}/empty/manifest.json", "cannot read the manifest"});
  }
  // A manifest naming a strand file that is missing: nothing is rendered, not
  // even the valid case before it.
  s.writeManifest(
      {{{"name", "fine"}, {"scene", kScene}},
       {{"name", "from-file"}, {"scene", "file:path=" + (s.dir / "missing.hair").string()}}});
  for (const std::string& cmd : {kCheck, kBless})
    s.expectRejected(cmd, {"{dir}/baselines/manifest.json", "case 'from-file'",
                           "{dir}/missing.hair", "No such file"});
}

// ------------------------------------------------------------------ shaders

// A technique shader with a syntax error (read through SB_SHADER_DIR): both
// backends name the file, the line and the technique.
TEST(BadInput, ShaderThatFailsToCompile) {
  Sandbox s;
  fs::create_directories(s.dir / "shaders");
  fs::copy(fs::path(SB_SOURCE_DIR) / "techniques", s.dir / "shaders" / "techniques",
           fs::copy_options::recursive);
  fs::copy(fs::path(SB_SOURCE_DIR) / "render", s.dir / "shaders" / "render",
           fs::copy_options::recursive);
  const fs::path broken = s.dir / "shaders/techniques/shadowmap/lookup.glsl";
  std::ofstream(broken, std::ios::app) << "this is not glsl;\n";
  int lines = 0;
  std::ifstream in(broken);
  for (std::string l; std::getline(in, l);) ++lines;
  s.freeze();
  const std::string env = "SB_SHADER_DIR=" + (s.dir / "shaders").string();
  const std::string where = "techniques/shadowmap/lookup.glsl:" + std::to_string(lines);
  for (const std::string backend : {"gl", "vulkan"}) {
    s.expectRejected("render --scene " + kScene + " --shadow shadowmap --size 16x16 --backend " +
                         backend + " --out {dir}/x.png",
                     {"shader compile error", where, "shadowmap"}, env);
    s.expectRejected("probe --scene stray:strands=50 --shadow shadowmap --backend " + backend +
                         " --out {dir}/p.csv",
                     {"shader compile error", where, "shadowmap"}, env);
  }
}

// ------------------------------------------------------------------ devices

TEST(BadInput, NoVulkanDevice) {
  Sandbox s;
  const std::string render = "render --scene " + kScene + " --size 16x16 --out {dir}/x.png";
  s.expectRejected(render + " --backend vulkan", {"no Vulkan device"}, kNoVulkan);
  s.expectRejected("probe --scene stray:strands=50 --backend vulkan --out {dir}/p.csv",
                   {"no Vulkan device"}, kNoVulkan);
  s.expectRejected("bench-oit --scene " + kScene + " --size 16x16 --backend vulkan",
                   {"no Vulkan device"}, kNoVulkan);
  // The case renders on GL first: no line is printed for it.
  s.expectRejected("check " + kCommittedCase + " --out {dir}/out", {"no Vulkan device"}, kNoVulkan);
  // GL still works.
  const CliResult gl = s.run(render + " --backend gl", kNoVulkan);
  EXPECT_EQ(gl.status, 0) << gl.err;
  EXPECT_TRUE(fs::exists(s.dir / "x.png"));
}

TEST(BadInput, NoGlContext) {
  Sandbox s;
  const std::string render = "render --scene " + kScene + " --size 16x16 --out {dir}/x.png";
  // No EGL vendor library: EGL (the default platform) has no display.
  s.expectRejected(render, {"no GL context", "EGL"}, kNoEgl);
  s.expectRejected("probe --scene stray:strands=50 --out {dir}/p.csv", {"no GL context"}, kNoEgl);
  s.expectRejected("bench-shadows --scene " + kScene + " --size 16x16 --repeat 1",
                   {"no GL context"}, kNoEgl);
  s.expectRejected("check " + kCommittedCase + " --out {dir}/out", {"no GL context"}, kNoEgl);
  // A driver that offers less than OpenGL 4.5: neither platform has a context.
  s.expectRejected(render + " --platform egl", {"no GL context", "EGL", "4.5"}, kNoGl45);
  s.expectRejected(render + " --platform osmesa", {"no GL context", "OSMesa", "4.5"}, kNoGl45);
  // Vulkan still works in both environments (and OSMesa without EGL).
  for (const auto& [env, args] : {std::pair{kNoEgl, render + " --backend vulkan"},
                                  std::pair{kNoGl45, render + " --backend vulkan"},
                                  std::pair{kNoEgl, render + " --platform osmesa"}}) {
    const CliResult r = s.run(args, env);
    EXPECT_EQ(r.status, 0) << env << " " << args << ": " << r.err;
    EXPECT_TRUE(fs::exists(s.dir / "x.png")) << env << " " << args;
    fs::remove(s.dir / "x.png");
  }
}

}  // namespace
