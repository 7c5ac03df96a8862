// A video is not read from stdin (docs/rk-extract.md, Inputs): a video is probed (ffprobe) and then decoded
// (ffmpeg) from its path, and a stream cannot be read twice; a recording arriving on a pipe is saved first
// (ffmpeg -i pipe:0 -c copy video.mkv).
#pragma once

#include <string>
#include <vector>

namespace rk::video {

// UsageError when a path is "-". FrameSource and ProbeVideo call it; the tools that take --video call it
// before reading anything.
void RefuseStdinVideo(const std::vector<std::string>& paths, const std::string& option = "--video");

}  // namespace rk::video
