#include "calibrate_gui/calibration_window.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include <opencv2/highgui.hpp>

#include "rle_vision/learning/calibration_view.h"

namespace rle_vision {
namespace {

const char* kFilesHelp =
    "drag: box around the object | u: undo | n/b: next/back frame | c: colour space | s: save | q: quit";
const char* kLiveHelp =
    "drag: box around the object (freezes the frame) | space: freeze/live | u: undo | n/b: next/back boxed "
    "frame | c: colour space | s: save | t: send to tracker | q: quit";

bool set(const char* variable) {
  const char* value = std::getenv(variable);
  return value != nullptr && value[0] != '\0';
}

}  // namespace

std::string displayProblem() {
  if (set("DISPLAY") || set("WAYLAND_DISPLAY")) return "";
  return "no display to open the calibration window on (DISPLAY is not set): run it on the robot's desktop, "
         "over 'ssh -X', or under a virtual one ('xvfb-run -a ...'); without a window, give the boxes on the "
         "command line (rle_vision_calibrate --name NAME IMAGE --box x0,y0,x1,y1)";
}

CalibrationWindow::CalibrationWindow(CalibrationSession* session, bool live, const std::string& title)
    : session_(session), live_(live), title_(title), showing_live_(live) {
  const std::string problem = displayProblem();
  if (!problem.empty()) throw std::runtime_error(problem);
  if (!live_ && session_->frameCount() > 0) current_ = 0;
  // GUI_NORMAL: no toolbar or zoom, so a mouse position on the window is a frame pixel.
  cv::namedWindow(title_, cv::WINDOW_AUTOSIZE | cv::WINDOW_GUI_NORMAL);
  cv::setMouseCallback(title_, &CalibrationWindow::onMouse, this);
}

CalibrationWindow::~CalibrationWindow() { cv::destroyWindow(title_); }

void CalibrationWindow::setLiveFrame(const cv::Mat& bgr) { live_frame_ = bgr; }

const cv::Mat& CalibrationWindow::shownFrame() const {
  static const cv::Mat kWaiting(240, 320, CV_8UC3, cv::Scalar(0, 0, 0));
  if (showing_live_ || current_ < 0) return live_frame_.empty() ? kWaiting : live_frame_;
  return session_->frame(current_).bgr;
}

void CalibrationWindow::onMouse(int event, int x, int y, int flags, void* self) {
  static_cast<CalibrationWindow*>(self)->mouse(event, x, y, flags);
}

void CalibrationWindow::mouse(int event, int x, int y, int flags) {
  const cv::Mat& frame = shownFrame();
  const cv::Point at(std::min(std::max(x, 0), frame.cols), std::min(std::max(y, 0), frame.rows));
  if (event == cv::EVENT_LBUTTONDOWN) {
    if (showing_live_) {
      if (live_frame_.empty()) return;  // nothing to box on yet
      // The box belongs to the frame it was started on: keep that frame.
      current_ = session_->addFrame(live_frame_.clone(), "live frame " + std::to_string(session_->frameCount() + 1));
      showing_live_ = false;
    }
    dragging_ = true;
    drag_start_ = at;
    drag_box_ = cv::Rect();
  } else if (event == cv::EVENT_MOUSEMOVE && dragging_ && (flags & cv::EVENT_FLAG_LBUTTON)) {
    drag_box_ = cv::Rect(drag_start_, at);
  } else if (event == cv::EVENT_LBUTTONUP && dragging_) {
    dragging_ = false;
    drag_box_ = cv::Rect();
    if (current_ >= 0) session_->addBox(current_, cv::Rect(drag_start_, at));
  }
}

CalibrationCommand CalibrationWindow::key(int code) {
  switch (code) {
    case 'q': case 27: return CalibrationCommand::kQuit;
    case 's': return CalibrationCommand::kSave;
    case 't': return live_ ? CalibrationCommand::kSendToTracker : CalibrationCommand::kNone;
    case 'u': session_->undo(); break;
    case 'c': session_->cycleSpace(); break;
    case ' ':
      if (live_ && showing_live_ && !live_frame_.empty()) {
        current_ = session_->addFrame(live_frame_.clone(), "live frame " + std::to_string(session_->frameCount() + 1));
        showing_live_ = false;
      } else if (live_) {
        showing_live_ = true;
      }
      break;
    case 'n': case 'b':
      if (session_->frameCount() > 0) {
        const int count = session_->frameCount(), from = current_ < 0 ? 0 : current_;
        current_ = (from + (code == 'n' ? 1 : count - 1)) % count;
        showing_live_ = false;
      }
      break;
    default: break;
  }
  return CalibrationCommand::kNone;
}

void CalibrationWindow::draw() {
  CalibrationView view;
  view.bgr = shownFrame();
  view.mask = session_->classMask(view.bgr);
  if (!showing_live_ && current_ >= 0) view.boxes = session_->frame(current_).boxes;
  view.dragging = drag_box_;
  view.status = calibrationStatus(*session_, CalibrationSession::countMask(view.mask, view.boxes));
  std::string where = showing_live_ ? "live" : "frame " + std::to_string(current_ + 1) + "/" +
                                                   std::to_string(session_->frameCount());
  if (!showing_live_ && current_ >= 0) {
    const std::string& name = session_->frame(current_).name;
    where += " " + name.substr(name.find_last_of('/') + 1);  // the file, not its folders
  }
  view.status.push_back(notice_.empty() ? where : where + " | " + notice_);
  view.help = live_ ? kLiveHelp : kFilesHelp;
  cv::imshow(title_, renderCalibrationView(view));
}

CalibrationCommand CalibrationWindow::step(int wait_ms) {
  draw();
  const int code = cv::waitKey(wait_ms);
  // The window's close button: the same as quitting.
  if (cv::getWindowProperty(title_, cv::WND_PROP_VISIBLE) < 1) return CalibrationCommand::kQuit;
  return code < 0 ? CalibrationCommand::kNone : key(code & 0xff);
}

}  // namespace rle_vision
