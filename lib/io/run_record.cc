#include "io/run_record.h"

#include <algorithm>
#include <iostream>
#include <mutex>

namespace rk::io {
namespace {

struct Record {
  std::mutex mutex;
  std::vector<InputRead> inputs;
  std::function<void(const std::string&)> sink;
};

Record& TheRecord() {
  static Record record;
  return record;
}

InputRead* FindLocked(Record& r, const std::string& path) {
  auto it = std::find_if(r.inputs.begin(), r.inputs.end(), [&](const InputRead& in) { return in.path == path; });
  return it == r.inputs.end() ? nullptr : &*it;
}

}  // namespace

void RecordInputRead(const std::string& path, std::optional<std::uintmax_t> bytes) {
  Record& r = TheRecord();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (InputRead* in = FindLocked(r, path)) {
    if (bytes) in->bytes = bytes;
    return;
  }
  r.inputs.push_back(InputRead{path, bytes, false, 0});
}

void RecordCsvRead(const std::string& path, std::size_t rows_skipped) {
  Record& r = TheRecord();
  std::lock_guard<std::mutex> lock(r.mutex);
  InputRead* in = FindLocked(r, path);
  if (!in) {
    r.inputs.push_back(InputRead{path, std::nullopt, false, 0});
    in = &r.inputs.back();
  }
  in->csv = true;
  in->rows_skipped += rows_skipped;
}

std::vector<InputRead> InputsRead() {
  Record& r = TheRecord();
  std::lock_guard<std::mutex> lock(r.mutex);
  return r.inputs;
}

std::optional<InputRead> FindInputRead(const std::string& path) {
  Record& r = TheRecord();
  std::lock_guard<std::mutex> lock(r.mutex);
  const InputRead* in = FindLocked(r, path);
  return in ? std::optional<InputRead>(*in) : std::nullopt;
}

void ClearInputsRead() {
  Record& r = TheRecord();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.inputs.clear();
}

void SetWarningSink(std::function<void(const std::string&)> sink) {
  Record& r = TheRecord();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.sink = std::move(sink);
}

void EmitWarning(const std::string& text) {
  std::function<void(const std::string&)> sink;
  {
    Record& r = TheRecord();
    std::lock_guard<std::mutex> lock(r.mutex);
    sink = r.sink;
  }
  if (sink) {
    sink(text);
  } else {
    std::cerr << "warning: " << text << "\n";
  }
}

}  // namespace rk::io
