#pragma once

// Buffers a step fills anew each time, with counts that creep up and down from step to step.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace sphys {

// Resizes `buffer` to `size`. When it must grow its capacity at least doubles, as push_back's
// does: std::vector's resize and assign may allocate exactly the size asked, and then a count
// that creeps up reallocates at every new maximum, so a step would never stop allocating.
template <class T>
void resize_buffer(std::vector<T>& buffer, std::size_t size) {
  if (size > buffer.capacity()) buffer.reserve(std::max(size, 2 * buffer.capacity()));
  buffer.resize(size);
}

// `size` copies of `value`, with resize_buffer's growth.
template <class T>
void fill_buffer(std::vector<T>& buffer, std::size_t size, const T& value) {
  resize_buffer(buffer, size);
  std::fill(buffer.begin(), buffer.end(), value);
}

}  // namespace sphys
