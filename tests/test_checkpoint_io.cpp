// The checkpoint byte format (solver/io/checkpoint_io.hpp): exact round trip, and every
// damaged file refused with a CheckpointError before any record is handed out.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "solver/io/checkpoint_io.hpp"

namespace fs = std::filesystem;
using namespace refmap;

namespace {

fs::path temp_file(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("refmap_ckio_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d / name;
}

std::string write_sample(const std::string& name, Field& f) {
  f.resize(7, 5, 2);
  for (int j = -2; j < 7; ++j)
    for (int i = -2; i < 9; ++i) f(i, j) = 0.1 * i - 3.7 * j + 1e-17 * i * j;
  CheckpointWriter w;
  w.put_i64("step", 42);
  w.put_f64("time", 0.1 + 0.2);
  w.put_string("scene", "name = \"x\"\n");
  w.put_field("u", f);
  const std::string p = temp_file(name).string();
  w.save(p);
  return p;
}

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void spit(const std::string& p, const std::string& s) {
  std::ofstream o(p, std::ios::binary | std::ios::trunc);
  o << s;
}

}  // namespace

TEST(CheckpointIO, RoundTripIsExact) {
  Field f;
  const std::string p = write_sample("round.ck", f);
  EXPECT_FALSE(fs::exists(p + ".tmp"));
  CheckpointReader r(p);
  EXPECT_EQ(r.get_i64("step"), 42);
  EXPECT_EQ(r.get_f64("time"), 0.1 + 0.2);  // bit for bit, not approximately
  EXPECT_EQ(r.get_string("scene"), "name = \"x\"\n");
  Field g;
  r.get_field("u", g);
  ASSERT_EQ(g.nx(), 7);
  ASSERT_EQ(g.ny(), 5);
  ASSERT_EQ(g.raw_size(), f.raw_size());
  for (std::size_t k = 0; k < f.raw_size(); ++k) ASSERT_EQ(g.raw()[k], f.raw()[k]) << k;
  EXPECT_TRUE(r.at_end());
}

/// The message with which reading the sample checkpoint, damaged by `damage`, is refused.
template <class F>
std::string refusal(const std::string& name, F damage) {
  Field f;
  const std::string p = write_sample(name, f);
  std::string s = slurp(p);
  damage(s);
  spit(p, s);
  try {
    CheckpointReader r(p);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

TEST(CheckpointIO, TruncatedFileIsRefused) {
  const std::string msg = refusal("trunc.ck", [](std::string& s) { s.resize(s.size() - 9); });
  EXPECT_NE(msg.find("truncated"), std::string::npos) << "accepted, or: " << msg;
}

TEST(CheckpointIO, FlippedByteIsRefused) {
  const std::string msg = refusal("flip.ck", [](std::string& s) { s[s.size() / 2] ^= 0x10; });
  EXPECT_NE(msg.find("checksum"), std::string::npos) << "accepted, or: " << msg;
}

TEST(CheckpointIO, OtherFilesAndLayoutsAreRefused) {
  const std::string p = temp_file("text.ck").string();
  spit(p, "[grid]\nnx = 4\n");
  EXPECT_THROW(CheckpointReader r(p), CheckpointError);
  EXPECT_THROW(CheckpointReader r(temp_file("missing.ck").string()), CheckpointError);
  Field f;
  CheckpointReader r(write_sample("order.ck", f));
  EXPECT_THROW(r.get_f64("time"), CheckpointError);  // the first record is "step"
}
