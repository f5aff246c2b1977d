#pragma once

#include <string>
#include <vector>

namespace lodestone::io {

/** `dir/name.rawlog.gz` -> `dir/name`: the stem beside which a rawlog's companions live
 * (`name.gt.tum`, `name.events.txt`, `name_Images/`). */
std::string rawlogStem(const std::string& rawlogPath);

/** True when the path asks for gzip compression (ends in ".gz"). */
bool isGzipPath(const std::string& path);

/** Throws std::invalid_argument naming both when `output` is one of `inputs` - the same file
 * by any name (a link, another relative path) - before anything opens it for writing, which
 * would truncate the input before it is read. */
void refuseOutputOverInput(const std::string& output, const std::vector<std::string>& inputs);

/** Makes an output file's folder if it is missing and checks that `path` is not a folder,
 * before any work: throws std::runtime_error naming the path otherwise. */
void prepareOutputFile(const std::string& path);

/** Where an output is written until it is complete: `path + ".partial"`. Writers (RawlogWriter,
 * TumTrajectoryWriter) write there and rename on close(), so a run that fails leaves a file
 * that says it is partial, never one that looks complete beside a previous run's outputs. */
std::string partialPath(const std::string& path);

/** Renames partialPath(path) over `path` (atomically, on one file system); throws
 * std::runtime_error naming both on failure. */
void commitPartial(const std::string& path);

}  // namespace lodestone::io
