// The tracker's blobs as rle_vision/Blob and cmvision-shaped messages.
#pragma once

#include <string>

#include "rle_vision/Blob.h"
#include "rle_vision/BlobArray.h"
#include "rle_vision/CmvisionBlobs.h"
#include "rle_vision/blob_tracker.h"
#include "rle_vision/color_table.h"

namespace rle_vision {

Blob blobToMsg(const TrackedBlob& blob, const std::string& color_name);

// The blobs in cmvision's message shape (cmvision/Blobs), ordered as cmvision orders them: by
// class, then by area (largest first); colours are the classes' display colours.
CmvisionBlobs cmvisionBlobsMsg(const BlobArray& blobs, const ColorTable& table);

}  // namespace rle_vision
