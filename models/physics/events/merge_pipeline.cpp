#include "aesim/events/merge_pipeline.hpp"

#include <memory>
#include <utility>

namespace aesim {

MergePipeline::MergePipeline(EventMerger& merger, std::size_t tiles) : merger_(merger), tiles_(tiles), worker_(1) {}

void MergePipeline::submit(TileRecords& filled, double before) {
  auto batch = std::make_shared<TileRecords>(std::move(filled));
  try {
    worker_.post([this, batch, before] {
      merger_.merge(*batch, before);
      std::lock_guard<std::mutex> lock(emptied_mutex_);
      emptied_.push_back(std::move(*batch));
    });
  } catch (...) {
    filled = std::move(*batch);
    throw;
  }
  // Once the batch before is being merged, the one before that has given its vectors back: after
  // the first two batches there is always one here.
  std::lock_guard<std::mutex> lock(emptied_mutex_);
  if (emptied_.empty()) {
    filled = TileRecords(tiles_);
  } else {
    filled = std::move(emptied_.back());
    emptied_.pop_back();
  }
}

void MergePipeline::drain() { worker_.drain(); }

}  // namespace aesim
