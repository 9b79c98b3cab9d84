#pragma once
// Inputs and outputs as one policy: before any work, a command's outputs are checked against its
// inputs and against what the file system allows, so that a refused command (exit 2) has changed
// nothing. An output that names an input (the same file after links: device and inode where the
// file exists, else the canonical folder and name) would destroy it; an output whose folder is
// missing or not writable would fail only after the work (and after a database was changed).
#include <string>
#include <vector>

namespace tilekit {

enum class PathRole {
  Input,            // read (only where it exists: a name that is no file, e.g. a built-in set, is no file)
  Output,           // a file written whole (base/atomic_file.hpp): its folder must exist and be writable
  OutputFolder,     // a folder replaced whole (AtomicFolder): its nearest existing parent must be writable
  OutputInNewFolder,  // a file written whole whose missing folders the command makes: as OutputFolder
  Database,         // a results database read (and perhaps written, where the command stores nothing new)
  WrittenDatabase,  // a results database the command stores into: its folder must exist and be writable
};

struct IoPath {
  std::string what;  // how the user named it (the CLI's flag), for the message
  std::string path;
  PathRole role = PathRole::Input;
  // The input (its `what`) this output may name: a checkpoint read whole on resume and then
  // written again in the same place.
  std::string may_replace;
};

// True if `a` and `b` name the same file: device and inode where both exist (links, hard links
// and "./x" vs "x" alike), else the same canonical folder and name. A path that exists is never
// the same as one that does not.
bool same_file(const std::string& a, const std::string& b);

// True if `path` lies inside the folder `folder` (both resolved), or is it.
bool inside_folder(const std::string& path, const std::string& folder);

// Throws InputError (exit 2) naming the paths when an output (a file, a folder, a written
// database) names an input or another output, when a folder output holds an input, or when an
// output's folder is missing, not a folder or not writable. A file directly inside an input
// folder (a folder of tiles) is an input too. Changes nothing on the disk.
void check_io_paths(const std::vector<IoPath>& paths);

// The databases among `paths` that a command stores into and that do not exist yet: what a refused
// run removes again (with SQLite's -journal, -wal and -shm beside them), so that a refusal creates
// no database (remove_created_files).
std::vector<std::string> databases_to_create(const std::vector<IoPath>& paths);
// Removes each file and its SQLite side files; the caller knows they were created by this run.
void remove_created_files(const std::vector<std::string>& paths);

}  // namespace tilekit
