// The calibration window (OpenCV highgui) over a CalibrationSession: drag a box around the
// object, see the class's mask on the frame with its pixel counts, undo, step through the
// frames, freeze a live camera, switch the colour space; save, send to the tracker and quit
// are handed back to the caller, who knows where the class goes.
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "rle_vision/learning/calibration_session.h"

namespace rle_vision {

enum class CalibrationCommand { kNone, kSave, kSendToTracker, kQuit };

// Empty when a window can open; otherwise the one line that says why not and what to do.
std::string displayProblem();

// Saves the session's class into the files (an empty path: not that one) and returns what the
// window's notice line should say: where it went, or why not.
std::string saveSessionClass(const CalibrationSession& session, const std::string& yaml_path,
                             const std::string& cmvision_path);

class CalibrationWindow {
 public:
  // live: frames come from a camera (setLiveFrame), shown until the user freezes one or
  // starts a box on one. Throws std::runtime_error(displayProblem()) without a display.
  CalibrationWindow(CalibrationSession* session, bool live, const std::string& title = "rle_vision calibrate");
  ~CalibrationWindow();
  CalibrationWindow(const CalibrationWindow&) = delete;
  CalibrationWindow& operator=(const CalibrationWindow&) = delete;

  void setLiveFrame(const cv::Mat& bgr);
  // A line shown under the status (what the last save or send did).
  void setNotice(const std::string& notice) { notice_ = notice; }
  // Draws, then handles the keys and mouse events of up to `wait_ms` ms.
  CalibrationCommand step(int wait_ms);

 private:
  // What the window shows: the camera, a camera frame held while a box is dragged on it (kept
  // only if the box is), or a frame of the session.
  enum class Shown { kLive, kHeld, kSessionFrame };

  static void onMouse(int event, int x, int y, int flags, void* self);
  void mouse(int event, int x, int y, int flags);
  void endDrag(const cv::Rect& box);
  CalibrationCommand key(int code);
  void keepLiveFrame();
  void stepFrames(int direction);
  const cv::Mat& shownFrame() const;
  bool closedByUser();
  void draw();

  CalibrationSession* session_;
  bool live_;
  std::string title_;
  std::string notice_;
  cv::Mat live_frame_;
  cv::Mat held_frame_;
  Shown shown_;
  int current_ = -1;  // the session frame shown as kSessionFrame
  bool dragging_ = false;
  cv::Point drag_start_;
  cv::Rect drag_box_;
  bool seen_visible_ = false;
  // The class mask of the frame shown, kept until the frame or the class changes (the frame
  // is held, so that no new frame can take its buffer's address).
  cv::Mat mask_frame_;
  int mask_revision_ = -1;
  cv::Mat mask_;
  MaskCounts mask_counts_;  // of mask_ in counted_boxes_
  std::vector<cv::Rect> counted_boxes_;
};

}  // namespace rle_vision
