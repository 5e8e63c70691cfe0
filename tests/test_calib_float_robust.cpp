// Bad inputs and outputs of sm_calibrate and sm_float_ref (label robust, docs/robustness.md
// "The tools: input checks and exit codes"): each case asserts the exit code (1 a bad input
// or output, 2 a command line CLI11 refuses), the one error line "TOOL: error: ..." naming
// the file or option, and that no output file is left. The inputs are made here: a
// synthetic chessboard rig (sm_chessboard_rig.hpp) and a small synthetic scene.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "float_ref/float_ref.hpp"
#include "sm_chessboard_rig.hpp"
#include "sm_cmd.hpp"
#include "sm_tool_expect.hpp"
#include "sm_test_util.hpp"
#include "toolio/sm_scenegen.hpp"

namespace fs = std::filesystem;

namespace {

using Run = sm::test::CmdResult;

fs::path root() { return fs::path(SM_TEST_TMP); }

Run run(const std::string& exe, const std::string& args) { return sm::test::run_cmd(exe, args, root()); }

using sm::test::expect_empty;
using sm::test::expect_error;

// The synthetic rig's boards (9 pairs, 640x480), written once per run of the test.
const fs::path& rig() {
  static const fs::path d = [] {
    const fs::path p = sm::test::fresh_dir(root() / "rig");
    sm::test::write_chessboard_rig(p);
    return p;
  }();
  return d;
}

// An empty output folder and a plain file, fresh for every test case; a small scene
// (64x48, 16 levels) as a one-scene dataset for sm_float_ref.
struct Fx {
  fs::path dir, out, file, scene;
  Fx() {
    dir = sm::test::fresh_dir(root() / "fx");
    out = dir / "out";
    fs::create_directories(out);
    file = dir / "afile";
    std::ofstream(file.string()) << "x";
    scene = dir / "data" / "small";
    const auto p = sm::test::scene_params(64, 48, 16, 2, 3);
    sm::tools::write_scene(sm::tools::render_scene(p), p, scene.string());
  }
  std::string o(const char* name) const { return (out / name).string(); }
  // sm_float_ref's fast settings on the scene: one pair, or the dataset
  std::string pair() const {
    return (scene / "left.png").string() + " " + (scene / "right.png").string() + " --levels 16 --census 5 --sw 3";
  }
  std::string dataset() const { return "--dataset " + (dir / "data").string() + " --levels 16 --census 5 --sw 3 -q"; }
};

}  // namespace

TEST_CASE("sm_calibrate: outputs that cannot be written are refused before any work", "[robust][calibrate]") {
  Fx fx;
  const std::string in = rig().string() + " ";
  const std::string nodir = (fx.out / "nodir" / "c.json").string(), f = fx.file.string();
  const std::string yaml = " --yaml " + fx.o("c.yaml"), json = " -o " + fx.o("c.json");
  for (const auto& [args, what] : std::vector<std::pair<std::string, std::string>>{
           {"-o " + nodir + yaml, "-o " + nodir + ": cannot write: folder "},
           {json + " --yaml " + f + "/c.yaml", "--yaml " + f + "/c.yaml: cannot write: " + f + " is not a folder"},
           {"-o " + fx.out.string() + yaml, "-o " + fx.out.string() + ": cannot write: is a folder"},
           {json + yaml + " --save-rectified " + f, "--save-rectified " + f + ": cannot write: not a folder"}}) {
    const Run r = run(SM_CALIBRATE_EXE, in + args);
    expect_error(r, 1, "sm_calibrate", what);
    CHECK(r.out.empty());  // no "board found" line: no image was read
    expect_empty(fx.out);
  }
}

TEST_CASE("sm_calibrate: -o and --yaml naming the same file", "[robust][calibrate]") {
  Fx fx;
  const std::string c = fx.o("c.json");
  const Run r = run(SM_CALIBRATE_EXE, rig().string() + " -o " + c + " --yaml " + (fx.out / "." / "c.json").string());
  expect_error(r, 1, "sm_calibrate", "--yaml " + (fx.out / "." / "c.json").string() + ": same file as -o");
  CHECK(r.out.empty());
  expect_empty(fx.out);
}

TEST_CASE("sm_calibrate: --check-vdisp when the board is found in no rectified pair", "[robust][calibrate]") {
  Fx fx;
  // at 32x24 the board is found in the 640x480 sources but in none of the rectified pairs
  const Run r = run(SM_CALIBRATE_EXE, fmt::format("{} --width 32 --height 24 --check-vdisp 0.5 -o {} --yaml {}",
                                                  rig().string(), fx.o("c.json"), fx.o("c.yaml")));
  expect_error(r, 1, "sm_calibrate",
               "--check-vdisp 0.5: the board was found in none of the 9 model-rectified pairs at 32x24");
  CHECK(r.err.find("exceeds") == std::string::npos);
  expect_empty(fx.out);
}

TEST_CASE("sm_calibrate: an image without its partner is refused", "[robust][calibrate]") {
  Fx fx;
  const fs::path boards = fx.dir / "boards";
  fs::create_directories(boards);
  for (int i = 0; i < 4; ++i)
    fs::copy_file(rig() / fmt::format("left{:02d}.png", i), boards / fmt::format("left{:02d}.png", i));
  for (int i = 0; i < 3; ++i)
    fs::copy_file(rig() / fmt::format("right{:02d}.png", i), boards / fmt::format("right{:02d}.png", i));
  const std::string o = fmt::format(" -o {} --yaml {}", fx.o("c.json"), fx.o("c.yaml"));
  Run r = run(SM_CALIBRATE_EXE, boards.string() + o);
  expect_error(r, 1, "sm_calibrate", boards.string() + ": 1 unpaired image: left03.png (no right03.png)");
  CHECK(r.out.empty());
  expect_empty(fx.out);
  // a right image without its left one, too (any case of the prefix)
  fs::remove(boards / "left03.png");
  fs::copy_file(rig() / "right04.png", boards / "Right07.png");
  r = run(SM_CALIBRATE_EXE, boards.string() + o);
  expect_error(r, 1, "sm_calibrate", "1 unpaired image: Right07.png (no left07.png)");
  expect_empty(fx.out);
}

TEST_CASE("sm_float_ref: outputs are checked before any work", "[robust][float_ref]") {
  Fx fx;
  const std::string nodir = (fx.out / "nodir" / "r.json").string(), f = fx.file.string();
  Run r = run(SM_FLOAT_REF_EXE, fx.dataset() + " --json " + nodir);
  expect_error(r, 1, "sm_float_ref", "--json " + nodir + ": cannot write: folder ");
  CHECK(r.out.empty());  // no table: no scene was scored
  r = run(SM_FLOAT_REF_EXE, fx.pair() + " --disp-file " + f + "/d.pfm");
  expect_error(r, 1, "sm_float_ref", "--disp-file " + f + "/d.pfm: cannot write: " + f + " is not a folder");
  expect_error(run(SM_FLOAT_REF_EXE, fx.pair() + " --disp-file " + fx.out.string()), 1, "sm_float_ref",
               "--disp-file " + fx.out.string() + ": cannot write: is a folder");
  expect_error(run(SM_FLOAT_REF_EXE, fx.pair() + " --disp-file " + fx.o("d.txt")), 1, "sm_float_ref",
               fx.o("d.txt") + ": --disp-file must end in .pfm or .png");
  expect_empty(fx.out);
}

TEST_CASE("sm_float_ref: an option of the other mode is refused when parsing", "[robust][float_ref]") {
  Fx fx;
  expect_error(run(SM_FLOAT_REF_EXE, fx.dataset() + " --disp-file " + fx.o("d.pfm")), 2, "sm_float_ref",
               "--dataset excludes --disp-file");
  expect_error(run(SM_FLOAT_REF_EXE, fx.pair() + " --disp-file " + fx.o("d.pfm") + " --json " + fx.o("r.json")), 2,
               "sm_float_ref", "--json requires --dataset");
  expect_error(run(SM_FLOAT_REF_EXE, fx.dataset() + " " + (fx.scene / "left.png").string()), 2, "sm_float_ref",
               "excludes");
  expect_empty(fx.out);
  // each mode with its own options still runs
  REQUIRE(run(SM_FLOAT_REF_EXE, fx.pair() + " --disp-file " + fx.o("d.pfm")).rc == 0);
  REQUIRE(run(SM_FLOAT_REF_EXE, fx.dataset() + " --json " + fx.o("r.json")).rc == 0);
  CHECK(fs::exists(fx.out / "d.pfm"));
  CHECK(fs::exists(fx.out / "r.json"));
}

TEST_CASE("sm_float_ref: a --simplify list with an empty item", "[robust][float_ref]") {
  Fx fx;
  for (const std::string v : {"shift,,round", "shift,", ",shift"})
    expect_error(run(SM_FLOAT_REF_EXE, fx.pair() + " --disp-file " + fx.o("d.pfm") + " --simplify " + v), 2,
                 "sm_float_ref", "--simplify: '" + v + "': an empty item in a ','-separated list");
  expect_empty(fx.out);
  // the library refuses it too (the tool's list is joined before it is parsed)
  CHECK_THROWS_AS(sm::fref::parse_simplify("shift,,round"), std::invalid_argument);
  CHECK_THROWS_AS(sm::fref::parse_simplify("round,"), std::invalid_argument);
  CHECK(sm::fref::simplify_string(sm::fref::parse_simplify("shift,round")) == "shift,round");
}
