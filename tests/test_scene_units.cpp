// The one unit registry (base/unit_registry.h) and the scene generators as units
// (scenes/scene_unit.h): each folder under scenes/generators/ registers scenes, nothing else
// lives there, and the registry refuses what would make a catalog ambiguous.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "base/unit_registry.h"
#include "scenes/scene.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;

struct Dummy {
  std::string name, folder;
};

TEST(UnitRegistry, FillsTheFolderAndRefusesATakenName) {
  sb::UnitRegistry<Dummy> r("widget", "things/widgets/");
  r.add("/src/things/widgets/round/unit.cpp", {.name = "round"});
  r.add("things/widgets/square/unit.cpp", {.name = "square"});
  ASSERT_NE(r.find("round"), nullptr);
  EXPECT_EQ(r.find("round")->folder, "round");
  EXPECT_EQ(r.get("square").folder, "square");
  EXPECT_EQ(r.all().size(), 2u);
  EXPECT_EQ(r.find("oval"), nullptr);
  // The control: a name given twice, a unit outside its root and one without a name stop the
  // program; an unknown name is the user's error, naming the closest.
  EXPECT_THROW(r.add("things/widgets/other/unit.cpp", {.name = "round"}), std::logic_error);
  EXPECT_THROW(r.add("elsewhere/oval/unit.cpp", {.name = "oval"}), std::logic_error);
  EXPECT_THROW(r.add("things/widgets/oval/unit.cpp", {}), std::logic_error);
  try {
    r.get("rond");
    FAIL() << "an unknown name was found";
  } catch (const sb::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'round'"), std::string::npos) << e.what();
  }
}

// The folders under `root`/scenes/generators that are no registered scene's, and loose files.
std::vector<std::string> foldersNotScenes(const fs::path& root) {
  std::set<std::string> units;
  for (const sb::SceneInfo& s : sb::sceneCatalog()) units.insert(s.folder);
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(root / "scenes" / "generators"))
    if (!e.is_directory() || !units.count(e.path().filename().string()))
      found.push_back("scenes/generators/" + e.path().filename().string());
  std::sort(found.begin(), found.end());
  return found;
}

TEST(SceneUnits, GeneratorsHoldUnitFoldersOnly) {
  std::string list;
  for (const auto& f : foldersNotScenes(SB_SOURCE_DIR)) list += "\n  " + f;
  EXPECT_TRUE(list.empty()) << "not a scene unit's folder (shared code goes in scenes/):" << list;
  // The check itself: a folder registering nothing and a loose file are found.
  const fs::path root = sbtest::tempDir("scene-units-only");
  fs::create_directories(root / "scenes" / "generators" / "fur");
  fs::create_directories(root / "scenes" / "generators" / "common");
  std::ofstream(root / "scenes" / "generators" / "loose.h") << "\n";
  EXPECT_EQ(foldersNotScenes(root),
            (std::vector<std::string>{"scenes/generators/common", "scenes/generators/loose.h"}));
}

TEST(SceneUnits, TheCatalogIsTheRegistryInItsOrder) {
  std::vector<std::string> names;
  for (const sb::SceneInfo& s : sb::sceneCatalog()) {
    names.push_back(s.name);
    EXPECT_TRUE(fs::is_regular_file(fs::path(SB_SOURCE_DIR) / "scenes" / "generators" / s.folder /
                                    "unit.cpp"))
        << s.name;
    EXPECT_FALSE(s.help.empty()) << s.name;
    // Every scene takes the options makeScene applies to all (SceneBase's), after its own.
    ASSERT_FALSE(s.options.empty());
    EXPECT_EQ(s.options.back().name, "instances") << s.name;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"straight", "wavy", "curly", "clustered", "fur",
                                             "stray", "sheet", "file"}));
}

}  // namespace
