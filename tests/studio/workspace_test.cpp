// The studio's sandbox: names refused without looking, symbolic links that leave the workspace,
// atomic writes, listings, and the upload type check by first bytes.

#include "workspace.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "sessions.hpp"
#include "temp_dir.hpp"

namespace exemplar::studio {
namespace {

namespace fs = std::filesystem;

class WorkspaceTest : public exemplar::testing::TempDirTest {
protected:
    void SetUp() override {
        TempDirTest::SetUp();
        fs::create_directories(dir_ / "ws" / "inner");
        fs::create_directories(dir_ / "outside");
        std::ofstream(dir_ / "outside" / "secret.txt") << "secret";
        std::ofstream(dir_ / "ws" / "inner" / "a.png") << "png";
        auto ws = Workspace::open((dir_ / "ws").string());
        ASSERT_TRUE(ws.ok()) << ws.status().message();
        ws_.emplace(std::move(*ws));
    }

    std::optional<Workspace> ws_;
};

TEST_F(WorkspaceTest, ResolvesRelativePathsInside) {
    auto p = ws_->resolve("inner/a.png");
    ASSERT_TRUE(p.ok()) << p.status().message();
    EXPECT_EQ(*p, fs::canonical(dir_ / "ws" / "inner" / "a.png"));
    auto fresh = ws_->resolve("new/folder/b.png");
    ASSERT_TRUE(fresh.ok()) << fresh.status().message();
    EXPECT_EQ(*fresh, fs::canonical(dir_ / "ws") / "new" / "folder" / "b.png");
}

TEST_F(WorkspaceTest, RefusesTraversalAbsoluteHiddenAndControlNames) {
    const std::string cases[] = {"",
                                 "..",
                                 "../outside/secret.txt",
                                 "inner/../../outside/secret.txt",
                                 "inner/..",
                                 "/etc/passwd",
                                 "//etc/passwd",
                                 "inner//a.png",
                                 "./inner/a.png",
                                 "inner/./a.png",
                                 ".hidden",
                                 "inner/.a.tmp-123456.png",
                                 "inner\\..\\..\\outside",
                                 std::string("inner/a\0.png", 12),
                                 "inner/a\n.png",
                                 "inner/",
                                 std::string(600, 'a')};
    for (const std::string& name : cases) {
        auto p = ws_->resolve(name);
        EXPECT_FALSE(p.ok()) << "accepted \"" << name << "\" as " << p->string();
        EXPECT_FALSE(ws_->read(name, 1 << 20).ok()) << name;
        EXPECT_FALSE(ws_->write(name, "x").is_ok()) << name;
    }
    std::string secret;
    std::ifstream(dir_ / "outside" / "secret.txt") >> secret;
    EXPECT_EQ(secret, "secret") << "a refused write changed a file outside";
}

TEST_F(WorkspaceTest, RefusesSymbolicLinksThatLeaveTheWorkspace) {
    fs::create_directory_symlink(dir_ / "outside", dir_ / "ws" / "door");
    fs::create_symlink(dir_ / "outside" / "secret.txt", dir_ / "ws" / "secret.txt");
    fs::create_symlink(dir_ / "ws" / "inner" / "a.png", dir_ / "ws" / "alias.png");
    for (const char* name : {"door/secret.txt", "door/new.png", "secret.txt", "door"}) {
        auto p = ws_->resolve(name);
        ASSERT_FALSE(p.ok()) << name;
        EXPECT_NE(p.status().message().find("outside the workspace"), std::string::npos);
    }
    EXPECT_FALSE(ws_->read("secret.txt", 100).ok());
    EXPECT_FALSE(ws_->write("door/new.png", "x").is_ok());
    EXPECT_FALSE(fs::exists(dir_ / "outside" / "new.png"));
    // A link that stays inside is followed.
    auto alias = ws_->read("alias.png", 100);
    ASSERT_TRUE(alias.ok()) << alias.status().message();
    EXPECT_EQ(*alias, "png");
    // Listings do not show links.
    for (const WorkspaceFile& f : ws_->list()) EXPECT_NE(f.path, "secret.txt");
}

TEST_F(WorkspaceTest, WritesAtomicallyIntoNewFoldersAndLeavesNoTemporaryFiles) {
    ASSERT_TRUE(ws_->write("out/deep/b.png", "bytes").is_ok());
    auto back = ws_->read("out/deep/b.png", 100);
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(*back, "bytes");
    EXPECT_FALSE(ws_->read("out/deep/b.png", 2).ok()) << "over the read limit";
    int entries = 0;
    for (const auto& e : fs::directory_iterator(dir_ / "ws" / "out" / "deep")) {
        EXPECT_EQ(e.path().filename(), "b.png");
        ++entries;
    }
    EXPECT_EQ(entries, 1);
}

TEST_F(WorkspaceTest, ListsVisibleFilesOnly) {
    std::ofstream(dir_ / "ws" / ".hidden.png") << "x";
    fs::create_directories(dir_ / "ws" / ".studio");
    std::ofstream(dir_ / "ws" / ".studio" / "c.png") << "x";
    const auto files = ws_->list();
    ASSERT_EQ(files.size(), 1u);
    EXPECT_EQ(files[0].path, "inner/a.png");
    EXPECT_EQ(files[0].bytes, 3u);
}

TEST(UploadType, RecognizesPngAndJpegByTheirFirstBytes) {
    EXPECT_EQ(*sniff_upload_type(std::string("\x89PNG\r\n\x1a\n....", 12)), UploadType::Png);
    EXPECT_EQ(*sniff_upload_type(std::string("\xff\xd8\xff\xe0", 4)), UploadType::Jpeg);
    EXPECT_FALSE(sniff_upload_type("<svg></svg>").ok());
    EXPECT_FALSE(sniff_upload_type(std::string("\x89PNG", 4)).ok());
    EXPECT_FALSE(sniff_upload_type("").ok());
}

}  // namespace
}  // namespace exemplar::studio

namespace exemplar::studio {
namespace {

TEST(History, UndoRedoAndTheLimitOfStepsBack) {
    History<int> history(0, 3);
    for (int i = 1; i <= 5; ++i) history.push(i);
    EXPECT_EQ(history.current(), 5);
    int undone = 0;
    while (history.undo()) ++undone;
    EXPECT_EQ(undone, 3) << "at most 3 steps back";
    EXPECT_EQ(history.current(), 2);
    EXPECT_TRUE(history.redo());
    history.push(9);  // drops the redo steps
    EXPECT_FALSE(history.can_redo());
    EXPECT_EQ(history.current(), 9);
    EXPECT_TRUE(history.undo());
    EXPECT_EQ(history.current(), 3);
    History<int> unlimited(0);
    for (int i = 1; i <= 100; ++i) unlimited.push(i);
    undone = 0;
    while (unlimited.undo()) ++undone;
    EXPECT_EQ(undone, 100);
}

}  // namespace
}  // namespace exemplar::studio
