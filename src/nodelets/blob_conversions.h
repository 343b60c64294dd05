// The tracker's blobs as rle_vision/Blob and cmvision-shaped messages.
#pragma once

#include <string>

#include "rle_vision/Blob.h"
#include "rle_vision/BlobArray.h"
#include "rle_vision/CmvisionBlobs.h"
#include "rle_vision/tracking/blob_tracker.h"
#include "rle_vision/color/color_table.h"

namespace rle_vision {

Blob blobToMsg(const TrackedBlob& blob, const std::string& color_name);

// The blobs in cmvision's message shape (cmvision/Blobs), with cmvision's conventions: `right`
// one past the last column (CMVision's x2), `bottom` the last row (its y2), x and y rounded as
// it rounds them. Ordered by class, then by area, largest first (what CMVision's sort means
// to do; it fails on large regions, see docs/operating.md); colours are the display colours.
CmvisionBlobs cmvisionBlobsMsg(const BlobArray& blobs, const ColorTable& table);

}  // namespace rle_vision
