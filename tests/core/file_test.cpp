// read_file(): a whole input in memory, refused beyond its limit, with the reason when it cannot be read.
#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <cutroute/core/file.hpp>

namespace cutroute {
namespace {

TEST(ReadFile, ReadsAFileWhole) {
  const auto path = std::filesystem::temp_directory_path() / ("cutroute-read-" + std::to_string(::getpid()));
  const std::string bytes = std::string("G1 X1\n") + '\0' + "\r\nend";
  std::ofstream(path, std::ios::binary) << bytes;
  auto r = read_file(path.string());
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(*r, bytes);
  // One byte over the limit is refused, naming the file and the limit.
  r = read_file(path.string(), bytes.size() - 1);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().file, path.string());
  EXPECT_EQ(r.error().message, "file is larger than 0 MB");
  EXPECT_TRUE(read_file(path.string(), bytes.size()).ok());
  std::filesystem::remove(path);
}

TEST(ReadFile, SaysWhyItCannot) {
  auto r = read_file("/nonexistent/cutroute/input.ngc");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "cannot open: No such file or directory");
  r = read_file(std::filesystem::temp_directory_path().string());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "is a directory, not a file");
}

// An input without a size (a pipe or FIFO) is read to its end, but an endless one stops at the
// limit; a device that reports a size of 0 (/dev/zero) reads as empty: `estimate /dev/zero` grew
// to 2.8 GB in 4 s.
TEST(ReadFile, AnEndlessInputEndsAtTheLimit) {
  std::signal(SIGPIPE, SIG_IGN);  // the writer below meets a closed pipe once the reader gives up
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  std::thread writer([fd = fds[1]] {
    const std::string block(1 << 16, 'G');
    while (::write(fd, block.data(), block.size()) > 0) {
    }
    ::close(fd);
  });
  const auto r = read_file("/proc/self/fd/" + std::to_string(fds[0]), 1 << 20);
  ::close(fds[0]);
  writer.join();
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "file is larger than 1 MB");
  if (std::filesystem::exists("/dev/zero")) {
    const auto zero = read_file("/dev/zero", 1 << 20);
    EXPECT_TRUE(!zero.ok() || zero->empty());
  }
}

}  // namespace
}  // namespace cutroute
