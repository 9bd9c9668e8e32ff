// The identity file (issue 41): made on the first run with mode 0600 (its directory
// 0700), the same identity read back, a file open to others or not an identity refused.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "../../support/temp_dir.hpp"
#include "net/identity_store.hpp"

using namespace fts::client;

TEST_CASE("Identity file: made once 0600, read back, refused when open to others", "[client][identity]") {
  fts::test::TempDir d;
  const std::string path = default_identity_path(d.path.string() + "/state");
  CHECK(path == d.path.string() + "/state/fear-the-sphere/identity");
  CHECK(default_identity_path("").empty());
  std::string why;
  const auto made = load_or_create_identity(path, why);
  REQUIRE(made);
  struct stat st {};
  REQUIRE(::stat(path.c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0600);
  REQUIRE(::stat((d.path / "state/fear-the-sphere").c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0700);
  const auto again = load_or_create_identity(path, why);
  REQUIRE(again);
  CHECK(again->public_key == made->public_key);
  CHECK(std::filesystem::directory_iterator(d.path / "state/fear-the-sphere") != std::filesystem::directory_iterator());
  CHECK(std::distance(std::filesystem::directory_iterator(d.path / "state/fear-the-sphere"),
                      std::filesystem::directory_iterator()) == 1);  // no temporary file left

  ::chmod(path.c_str(), 0644);
  CHECK_FALSE(load_or_create_identity(path, why));
  CHECK_THAT(why, Catch::Contains("may be read by others (mode 644)"));

  const std::string junk = (d.path / "junk").string();
  std::ofstream(junk) << "ssh-ed25519 AAAAC3NzaC1lZDI1NTE5 me\n";
  ::chmod(junk.c_str(), 0600);
  CHECK_FALSE(load_or_create_identity(junk, why));
  CHECK_THAT(why, Catch::Contains("is not a Fear The Sphere identity"));
}
