#include "run/step_progress.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/progress.h"

namespace rk::run::internal {

void StepProgressFiles::Start(std::function<void(const std::string&)> show) {
  if (!show || thread_.joinable()) return;
  show_ = std::move(show);
  stop_ = false;
  thread_ = std::thread([this] { Watch(); });
}

void StepProgressFiles::Stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  std::lock_guard<std::mutex> lock(mu_);
  std::error_code ec;
  for (const auto& [id, e] : files_) std::filesystem::remove(e.file, ec);  // steps stopped by a signal
  files_.clear();
}

std::string StepProgressFiles::Add(const std::string& step_id, const std::string& file) {
  if (!show_) return "";
  std::lock_guard<std::mutex> lock(mu_);
  files_[step_id] = {file, std::chrono::steady_clock::now()};
  return std::string(io::ProgressMeter::kProgressFileEnv) + "=" + file;
}

void StepProgressFiles::Remove(const std::string& step_id) {
  std::lock_guard<std::mutex> lock(mu_);
  const auto it = files_.find(step_id);
  if (it == files_.end()) return;
  std::error_code ec;
  std::filesystem::remove(it->second.file, ec);
  files_.erase(it);
}

std::string StepProgressFiles::Line() const {
  std::lock_guard<std::mutex> lock(mu_);
  std::string line;
  const auto now = std::chrono::steady_clock::now();
  for (const auto& [id, e] : files_) {
    std::ifstream f(e.file);
    std::string text;
    if (!std::getline(f, text)) continue;  // not written yet, or being rewritten
    std::istringstream in(text);
    long long done = 0, total = 0;
    std::string unit;
    if (!(in >> done >> total >> unit)) continue;
    const double elapsed = std::chrono::duration<double>(now - e.start).count();
    if (!line.empty()) line += " | ";
    line += io::FormatProgress(id, unit, done, total, elapsed);
  }
  return line;
}

void StepProgressFiles::Watch() {
  std::string last;
  while (!stop_) {
    const std::string line = Line();
    if (!line.empty() && line != last) show_(line);
    last = line;
    for (int i = 0; i < 10 && !stop_; ++i) std::this_thread::sleep_for(std::chrono::duration<double>(kRedrawS / 10));
  }
}

}  // namespace rk::run::internal
