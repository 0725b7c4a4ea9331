#pragma once
/// \file
/// Output folders: every writer creates the folders a destination needs, as Blender does
/// (`exemplar animate -o out/shots/%04d.png` on a fresh checkout just works).

#include <string>

#include "exemplar/core/status.hpp"

namespace exemplar {

/// Creates the folder that will hold the file `path` (with any missing parents); nothing to do
/// when it exists or `path` has no folder part. On failure (IoError) one line names `path`, the
/// folder and the reason, e.g. `out/x/a.png: cannot create folder "out/x": out is a file, not a
/// folder`.
Status create_parent_folders(const std::string& path);

/// Creates `folder` itself (with any missing parents), for outputs that are folders (a render's
/// buffers). Same errors as create_parent_folders, naming `folder`.
Status create_folders(const std::string& folder);

/// Checks, without creating anything, that create_parent_folders(path) can succeed: the nearest
/// existing ancestor of its folder is a writable folder. Same messages; for checks made before a
/// long run, so that a run that fails its checks leaves no folders behind.
Status check_parent_folders(const std::string& path);

/// As check_parent_folders, for create_folders(folder).
Status check_folders(const std::string& folder);

}  // namespace exemplar
