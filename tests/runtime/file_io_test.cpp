// file_io: only regular files are read, within a size limit, and stream file names resolve
// inside their folder.
#include "sm2/runtime/file_io.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace sm2::runtime {
namespace {

namespace fs = std::filesystem;

class FileIo : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("sm2_file_io_" + std::to_string(getpid()));
        fs::create_directories(dir_ / "stream");
    }
    void TearDown() override { fs::remove_all(dir_); }
    [[nodiscard]] std::string path(const std::string& name) const { return (dir_ / name).string(); }
    fs::path dir_;
};

TEST_F(FileIo, ReadsRegularFilesUpToTheLimit) {
    std::ofstream(path("five.bin"), std::ios::binary) << "12345";
    std::string error;
    const auto bytes = read_file_limited(path("five.bin"), 5, error);
    ASSERT_TRUE(bytes) << error;
    ASSERT_EQ(bytes->size(), 5u);
    EXPECT_EQ(static_cast<char>((*bytes)[4]), '5');
    EXPECT_FALSE(read_file_limited(path("five.bin"), 4, error));
    EXPECT_EQ(error, path("five.bin") + ": larger than the 4-byte limit for an input file (5 bytes)");
    EXPECT_TRUE(check_input_file(path("five.bin"), 5, error));
    EXPECT_FALSE(check_input_file(path("five.bin"), 4, error));
}

TEST_F(FileIo, DirectoriesDevicesAndFifosAreRefusedWithoutReading) {
    std::string error;
    EXPECT_FALSE(read_file_limited(path("stream"), kMaxInputFileBytes, error));
    EXPECT_EQ(error, path("stream") + ": is a directory");
    EXPECT_FALSE(read_file_limited("/dev/zero", kMaxInputFileBytes, error));
    EXPECT_EQ(error, "/dev/zero: is a character device, not a regular file");
    // A FIFO with no writer: a blocking open would wait forever.
    ASSERT_EQ(mkfifo(path("fifo").c_str(), 0600), 0);
    EXPECT_FALSE(read_file_limited(path("fifo"), kMaxInputFileBytes, error));
    EXPECT_EQ(error, path("fifo") + ": is a FIFO (named pipe), not a regular file");
    EXPECT_FALSE(check_input_file(path("fifo"), kMaxInputFileBytes, error));
    EXPECT_FALSE(check_input_file("/dev/zero", kMaxInputFileBytes, error));
    EXPECT_FALSE(read_file_limited(path("missing"), kMaxInputFileBytes, error));
    EXPECT_EQ(error, path("missing") + ": cannot open: No such file or directory");
}

TEST_F(FileIo, ResolveInsideKeepsPathsInTheRoot) {
    const std::string root = path("stream");
    std::string error;
    const auto inside = resolve_inside(root, root, "sub/../a.png", error);
    ASSERT_TRUE(inside) << error;
    EXPECT_EQ(*inside, (fs::canonical(root) / "a.png").string());
    EXPECT_FALSE(resolve_inside(root, root, "/etc/passwd", error));
    EXPECT_EQ(error, "'/etc/passwd' is an absolute path; streams may name files only relative to their folder");
    EXPECT_FALSE(resolve_inside(root, root, "../x", error));
    EXPECT_NE(error.find("outside"), std::string::npos) << error;
    EXPECT_FALSE(resolve_inside(root, root, "", error));
    // A symbolic link out of the root is followed, and refused; one inside it is fine.
    fs::create_directory_symlink(dir_, path("stream/up"));
    std::ofstream(path("stream/real.txt")) << "x";
    fs::create_symlink(path("stream/real.txt"), path("stream/alias.txt"));
    EXPECT_FALSE(resolve_inside(root, root, "up/secret", error));
    EXPECT_TRUE(resolve_inside(root, root, "alias.txt", error)) << error;
    // A wider root admits what the narrow one refused.
    EXPECT_TRUE(resolve_inside(path(""), root, "../x", error)) << error;
    EXPECT_TRUE(resolve_inside(path(""), root, "up/secret", error)) << error;
    // The root's prefix as a string is not enough: "stream2" is not inside "stream".
    fs::create_directories(path("stream2"));
    EXPECT_FALSE(resolve_inside(root, root, "../stream2/x", error));
}

}  // namespace
}  // namespace sm2::runtime
