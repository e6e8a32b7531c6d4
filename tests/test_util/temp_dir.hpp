#pragma once
// The one way tests make scratch folders and temporary files.
//
// CTest runs every test case in its own process, several at once, so a scratch path must never be
// derived from a fixed name, the test name or an unseeded random number: two processes would share
// the folder and delete each other's files. A TempDir is a fresh folder under the system temp dir
// (TMPDIR), created atomically with a name made of the process id, a per-process counter and a
// random number, and removed with everything in it when the object goes away. Temporary files the
// tests write go inside one (file() / write()).

#include <filesystem>
#include <string>
#include <string_view>

namespace telear::test_files {

class TempDir {
 public:
  // `label` only makes the folder's name readable: <tmp>/telear_<label>_<pid>_<n>_<random>.
  explicit TempDir(std::string_view label = "test");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  TempDir(TempDir&&) = delete;
  TempDir& operator=(TempDir&&) = delete;

  // The folder itself (exists, empty at construction).
  const std::filesystem::path& path() const { return path_; }
  // path() as a string.
  std::string string() const { return path_.string(); }
  // path()/relative as a string, for a file or folder a test (or the code under test) will create;
  // the parent folders of `relative` are created, the entry itself is not.
  std::string file(const std::string& relative) const;
  // Writes `text` to path()/relative (creating folders) and returns the full path.
  std::string write(const std::string& relative, const std::string& text) const;

 private:
  std::filesystem::path path_;
};

}  // namespace telear::test_files
