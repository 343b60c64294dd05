// A colour table that one thread replaces while others segment frames with it.
// Readers take a reference-counted snapshot (the pointer copy is atomic); the table itself is
// immutable, so no lock is held while a frame is segmented and a swap never waits for a frame.
#pragma once

#include <atomic>
#include <memory>

#include "rle_vision/color/color_table.h"

namespace rle_vision {

class SharedColorTable {
 public:
  std::shared_ptr<const ColorTable> load() const { return std::atomic_load(&table_); }
  void store(std::shared_ptr<const ColorTable> table) { std::atomic_store(&table_, std::move(table)); }

 private:
  std::shared_ptr<const ColorTable> table_;
};

}  // namespace rle_vision
