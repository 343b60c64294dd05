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
  static void onMouse(int event, int x, int y, int flags, void* self);
  void mouse(int event, int x, int y, int flags);
  CalibrationCommand key(int code);
  const cv::Mat& shownFrame() const;
  void draw();

  CalibrationSession* session_;
  bool live_;
  std::string title_;
  std::string notice_;
  cv::Mat live_frame_;
  bool showing_live_;
  int current_ = -1;  // the session frame shown when not showing the live one
  bool dragging_ = false;
  cv::Point drag_start_;
  cv::Rect drag_box_;
};

}  // namespace rle_vision
