#pragma once
// The page's files -- the esbuild bundle of web/ (index.html, app.js, app.css) that the build
// writes to build/web and the install to share/telear/web -- and how a request's path maps to
// one of them. Nothing outside that folder is ever served: a path with "..", a backslash, a NUL
// or an absolute form is refused before the file system is touched.

#include <optional>
#include <string>

#include "telear/core/result.hpp"

namespace telear::web {

// The folder with the page, in order: `given` when not empty; $TELEAR_WEB_ROOT; beside an
// installed program (BINDIR/../share/telear/web); this build tree's bundle; the install
// prefix's. The first that holds index.html; else an error naming every place looked at.
Result<std::string> find_page_root(const std::string& given = {});

struct PageFile {
  std::string body;
  std::string content_type;  // "text/html; charset=utf-8", "text/javascript" ...
};

// The file a GET of `target` (the request target, query string allowed and ignored) names in
// `root`: "/" is index.html. nullopt: no such file, or a path that leaves the folder.
std::optional<PageFile> read_page_file(const std::string& root, const std::string& target);

// The media type of a file name by its extension (application/octet-stream when unknown).
std::string content_type_of(const std::string& name);

}  // namespace telear::web
