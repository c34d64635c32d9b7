#include <gtest/gtest.h>

#include <filesystem>

#include "common/files.h"

TEST(Files, Sha256KnownVectors) {
  // FIPS 180-2, appendix B.1, and the empty string.
  EXPECT_EQ(fc::sha256Hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(fc::sha256Hex(""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Files, AtomicWriteAndHash) {
  const std::string p = ::testing::TempDir() + "/atomic.txt";
  fc::writeFileAtomic(p, "abc");
  EXPECT_EQ(fc::readTextFile(p), "abc");
  EXPECT_EQ(fc::sha256File(p), fc::sha256Hex("abc"));
  EXPECT_THROW(fc::writeFileAtomic("/nonexistent/dir/x.txt", "a"), std::runtime_error);
}

TEST(Files, RelativePaths) {
  EXPECT_EQ(fc::resolveRelativeTo("a/b/scene.yaml", "mats.yaml"), "a/b/mats.yaml");
  EXPECT_EQ(fc::resolveRelativeTo("scene.yaml", "mats.yaml"), "mats.yaml");
  EXPECT_EQ(fc::resolveRelativeTo("a/scene.yaml", "/abs/m.yaml"), "/abs/m.yaml");
  EXPECT_EQ(fc::directoryOf("/x.yaml"), "/");
}
