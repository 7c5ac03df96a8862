// Unit tests of run/digest: the size+mtime digest shortcut and image-sequence patterns.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/stat.h>

#include <filesystem>
#include <string>
#include <vector>

#include "io/error.h"
#include "run/digest.h"
#include "run/sha256.h"
#include "run_test_util.h"

namespace rk::run {
namespace {
namespace fs = std::filesystem;
using testing::TempDir;
using testing::Write;

TEST(Digest, SizeMtimeShortcutAndContentHash) {
  TempDir d;
  Write(d / "a.csv", "t_s,x\n0,1\n");
  DigestCache first(d.path(), io::Json(), true);
  const FileDigest a = first.Digest("a.csv");
  EXPECT_TRUE(a.hashed);
  EXPECT_EQ(a.sha256, Sha256Hex("t_s,x\n0,1\n"));
  EXPECT_THROW(first.Digest("missing.csv"), Error);

  // Same size and mtime: the recorded hash is trusted (even a deliberately wrong one, which shows that
  // the file was not read); --rehash reads it.
  io::Json prev = first.ToJson();
  prev["a.csv"]["sha256"] = "recorded";
  DigestCache second(d.path(), prev, true);
  EXPECT_EQ(second.Digest("a.csv").sha256, "recorded");
  EXPECT_FALSE(second.Digest("a.csv").hashed);
  DigestCache rehash(d.path(), prev, false);
  EXPECT_EQ(rehash.Digest("a.csv").sha256, a.sha256);

  // A touch changes mtime only: hashed again, same content hash.
  struct timespec ts[2] = {{0, UTIME_NOW}, {1, 0}};
  ASSERT_EQ(::utimensat(AT_FDCWD, (d / "a.csv").c_str(), ts, 0), 0);
  DigestCache third(d.path(), first.ToJson(), true);
  EXPECT_TRUE(third.Digest("a.csv").hashed);
  EXPECT_EQ(third.Digest("a.csv").sha256, a.sha256);
  // New content: new hash.
  Write(d / "a.csv", "t_s,x\n0,2\n");
  DigestCache fourth(d.path(), first.ToJson(), true);
  EXPECT_NE(fourth.Digest("a.csv").sha256, a.sha256);
}

TEST(Digest, ImageSequencePattern) {
  TempDir d;
  for (int i : {0, 1, 2, 10}) {
    char name[32];
    std::snprintf(name, sizeof name, "seq/%06d.png", i);
    Write(d / name, "frame" + std::to_string(i));
  }
  Write(d / "seq/notes.txt", "x");
  EXPECT_TRUE(IsSequencePattern("seq/%06d.png"));
  EXPECT_FALSE(IsSequencePattern("seq/video.mkv"));
  const auto files = ExpandSequence(d / "seq/%06d.png");
  ASSERT_EQ(files.size(), 4u);
  EXPECT_EQ(fs::path(files.back()).filename(), "000010.png");
  DigestCache c(d.path(), io::Json(), true);
  const FileDigest s = c.Digest("seq/%06d.png");
  EXPECT_EQ(s.files, 4u);
  Write(d / "seq/000002.png", "changed");
  DigestCache c2(d.path(), io::Json(), true);
  EXPECT_NE(c2.Digest("seq/%06d.png").sha256, s.sha256);
  EXPECT_THROW(c2.Digest("seq/%04d.jpg"), Error);
}

}  // namespace
}  // namespace rk::run
