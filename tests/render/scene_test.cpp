// Scene files: the built-in scenes parse, the examples equal them, and every kind of bad input
// gets one line naming the file and the key.

#include "exemplar/render/scene.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace exemplar::render {
namespace {

namespace fs = std::filesystem;

std::string minimal(const std::string& object_extra = "", const std::string& top_extra = "") {
    return R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},)" + top_extra +
           R"( "materials": [{"name": "m"}],
              "objects": [{"shape": "sphere", "material": "m")" +
           object_extra + "}]}";
}

void expect_error(const std::string& json, const std::string& part) {
    auto scene = parse_scene(json, "s.json", ".");
    ASSERT_FALSE(scene.ok()) << json;
    const std::string& message = scene.status().message();
    EXPECT_EQ(message.rfind("s.json: ", 0), 0u) << message;
    EXPECT_NE(message.find(part), std::string::npos) << "expected '" << part << "' in " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(Scene, MinimalSceneParses) {
    auto scene = parse_scene(minimal(), "s.json", ".");
    ASSERT_TRUE(scene.ok()) << scene.status().message();
    ASSERT_EQ(scene->meshes.size(), 1u);
    EXPECT_EQ(scene->meshes[0].object_id, 1);
    EXPECT_EQ(scene->meshes[0].normals.size(), scene->meshes[0].positions.size());
}

TEST(Scene, BuiltinScenesParseAndEqualTheExampleFiles) {
    for (const std::string& name : builtin_scene_names()) {
        auto scene = builtin_scene(name);
        ASSERT_TRUE(scene.ok()) << name << ": " << scene.status().message();
        EXPECT_GE(scene->meshes.size(), 3u);
        EXPECT_EQ(scene->lights.size(), 1u);
        std::ifstream in(EXEMPLAR_SOURCE_DIR "/examples/render/" + name + ".json");
        std::ostringstream text;
        text << in.rdbuf();
        EXPECT_EQ(text.str(), builtin_scene_json(name).value()) << name;
    }
    auto unknown = builtin_scene("teapot");
    ASSERT_FALSE(unknown.ok());
    EXPECT_NE(unknown.status().message().find("sphere-on-table"), std::string::npos);
}

TEST(Scene, SpotMeshLoadsThroughTinyObjLoader) {
    auto scene = load_scene(EXEMPLAR_SOURCE_DIR "/examples/render/spot-on-table.json");
    ASSERT_TRUE(scene.ok()) << scene.status().message();
    EXPECT_EQ(scene->meshes[0].triangles.size(), 5856u);
    // normalize + scale 2.2: the mesh stands on the table, 2.2 high.
    float lo = 1e9f, hi = -1e9f;
    for (const auto& p : scene->meshes[0].positions) {
        lo = std::min(lo, p[1]);
        hi = std::max(hi, p[1]);
    }
    EXPECT_NEAR(lo, 0.0f, 1e-4f);
    EXPECT_NEAR(hi, 2.2f, 1e-3f);
}

TEST(Scene, UnknownKeysAreNamed) {
    expect_error(R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0], "fov": 30}})",
                 "camera.fov: unknown key");
    expect_error(minimal(", \"colour\": 1"), "objects[0].colour: unknown key");
    expect_error(minimal("", R"( "lightz": [],)"), "lightz: unknown key");
}

TEST(Scene, BadValuesAreNamed) {
    expect_error(minimal("", R"( "lights": [{"center": [0, 5, 0], "look_at": [0, 0, 0],
                                            "width": -1}],)"),
                 "lights[0].width: -1 is invalid (must be > 0");
    expect_error(R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0], "fov_deg": 200}})",
                 "camera.fov_deg: 200 is invalid");
    expect_error(R"({"camera": {"position": [0, 1], "look_at": [0, 1, 0]}})",
                 "camera.position: [0,1] is invalid");
    expect_error(minimal(", \"shape\": \"cube\""), "");  // duplicate key: JSON keeps the last
    expect_error(R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
                     "objects": [{"shape": "cube", "material": "m"}]})",
                 "objects[0].shape: \"cube\" is invalid");
    expect_error(R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
                     "objects": [{"shape": "sphere", "material": "nope"}]})",
                 "objects[0].material: \"nope\" is not defined");
    expect_error(R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
                     "materials": [{"name": "m", "diffuse": [0.9, 0.9, 0.9],
                                    "specular": [0.2, 0.2, 0.2]}],
                     "objects": [{"shape": "sphere", "material": "m"}]})",
                 "materials[0]: diffuse + specular must be <= 1");
    expect_error(R"({"objects": []})", "camera: missing");
    expect_error("{\"camera\": ", "not valid JSON");
}

TEST(Scene, MissingMeshFileIsNamed) {
    expect_error(R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
                     "materials": [{"name": "m"}],
                     "objects": [{"shape": "mesh", "file": "nowhere/bunny.obj", "material": "m"}]})",
                 "objects[0].file: ./nowhere/bunny.obj: no such file");
}

TEST(Scene, MeshPathsAreRelativeToTheSceneFile) {
    const fs::path dir =
        fs::temp_directory_path() / ("exemplar_scene_" + std::to_string(::getpid()));
    fs::create_directories(dir / "sub");
    std::ofstream(dir / "sub" / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(dir / "scene.json")
        << R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
               "materials": [{"name": "m"}],
               "objects": [{"shape": "mesh", "file": "sub/tri.obj", "material": "m"}]})";
    auto scene = load_scene((dir / "scene.json").string());
    EXPECT_TRUE(scene.ok()) << scene.status().message();
    auto missing = load_scene((dir / "none.json").string());
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.status().message().find("none.json: no such file"), std::string::npos);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace exemplar::render
