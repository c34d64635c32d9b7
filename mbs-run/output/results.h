#pragma once
// Writing a run's results: the HDF5 layout of contracts.md ("results/1") and
// CSV extracts of chosen channels, both streamed: rows are written as the run
// takes them (chunked, extendible datasets; a bounded buffer whatever the
// output step) to a temporary file that is renamed into place at the end.
// A run stopped early (signal, solver failure) still finishes its file, with
// `status` saying why; a write error (full disk) removes the temporary and
// leaves any previous file untouched.
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/h5io.h"
#include "mbs-run/model/model.h"
#include "mbs-run/run/history.h"

namespace fc::mbs {

// One output channel: its results path without the leading slash (e.g.
// "joints/R3/angle"), its columns, and how a row is read from a Sample.
struct Channel {
  std::string name;
  int columns = 1;
  bool rank1 = true;  // (n_out) dataset rather than (n_out, columns)
  std::function<void(const Sample&, double*)> read;
  // Trailing dimensions of a dataset of rank > 2 (their product is `columns`),
  // e.g. (n_elements, n_plies, 3) of ply_stress; empty for rank 1 and 2.
  std::vector<hsize_t> dims = {};
  // A full stress field (or /stress_time): with outputs.stress_every K it gets
  // only rows 0, K, 2K, ... and the last (docs/stresses.md).
  bool decimated = false;
};
// "distances/A-B": the contact monitor's channel of Model::distance_pairs[k].
std::string distanceChannel(const Model& model, std::size_t k);
// Every channel the scene's results hold, in file order.
std::vector<Channel> resultChannels(const Model& model);

class ResultsFileWriter : public SampleSink {
 public:
  // Creates the temporary beside `path`; expected_rows sizes the chunks.
  ResultsFileWriter(const std::string& path, const Model& model, long expected_rows);
  ~ResultsFileWriter() override;
  // Buffers the row; writes the buffer when full, and at least every
  // flush_seconds, flushing the file. Write errors throw OutputError.
  void write(const Sample& s) override;
  // Writes the rest and the run's root attributes, then renames the file into place.
  void finish(const Model& model, const RunSummary& r, const std::string& inputs_sha256);
  long rowsWritten() const { return static_cast<long>(written_); }

 private:
  void writeBlock();

  std::vector<Channel> channels_;
  fc::AtomicH5Writer file_;
  std::vector<hid_t> datasets_;
  std::vector<std::vector<double>> buffers_;  // per channel, row-major block
  unsigned long long block_rows_ = 0, buffered_ = 0, written_ = 0;
  // Decimation of the full stress fields (Model::stress_every): rows written
  // per channel, and the latest row the decimated channels skipped, which
  // finish() appends so that the final state is always there.
  unsigned long long every_ = 1;
  std::vector<unsigned long long> channel_rows_;
  std::vector<std::vector<double>> skipped_;
  bool skipped_pending_ = false;
  std::chrono::steady_clock::time_point last_flush_;
};

class CsvWriter : public SampleSink {
 public:
  // Channels as in resultChannels (time always first); unknown names throw
  // std::invalid_argument listing the valid ones, before anything is written.
  CsvWriter(const std::string& path, const Model& model, const std::vector<std::string>& channels);
  ~CsvWriter() override;
  void write(const Sample& s) override;
  void finish();  // writes the rest, fsyncs and renames into place

 private:
  void drain();

  std::string path_, tmp_path_;
  std::vector<Channel> chosen_;
  int fd_ = -1;
  std::string buffer_;
  std::unique_ptr<fc::TemporaryRegistration> registration_;
};

// The same from rows kept in memory.
void writeResults(const std::string& path, const Model& model, const Results& results,
                  const std::string& inputs_sha256);
void writeCsv(const std::string& path, const Model& model, const Results& results,
              const std::vector<std::string>& channels);

}  // namespace fc::mbs
