#include "calibrate_gui/calibration_window.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include <opencv2/highgui.hpp>

#include "rle_vision/io/color_config.h"
#include "rle_vision/learning/calibration_view.h"

namespace rle_vision {
namespace {

const char* kFilesHelp =
    "drag: box around the object | u: undo | n/b: next/back frame | c: colour space | s: save | q: quit";
const char* kLiveHelp =
    "drag: box around the object (freezes the frame) | space: freeze/live | u: undo | n/b: next/back kept "
    "frame | c: colour space | s: save | t: send to tracker | q: quit";

// The box between two corner pixels, both inside it (x1,y1 one past the last: the frame's
// last column and row can be boxed).
cv::Rect boxBetween(cv::Point a, cv::Point b) {
  return cv::Rect(cv::Point(std::min(a.x, b.x), std::min(a.y, b.y)),
                  cv::Point(std::max(a.x, b.x) + 1, std::max(a.y, b.y) + 1));
}

}  // namespace

std::string displayProblem() {
  const char* display = std::getenv("DISPLAY");
  if (display != nullptr && display[0] != '\0') return "";
  return "no display to open the calibration window on (DISPLAY is not set): run it on the robot's desktop, "
         "over 'ssh -X', or under a virtual one ('xvfb-run -a ...'); without a window, give the boxes on the "
         "command line (rle_vision_calibrate --name NAME IMAGE --box x0,y0,x1,y1)";
}

std::string saveSessionClass(const CalibrationSession& session, const std::string& yaml_path,
                             const std::string& cmvision_path) {
  if (!session.result()) return "nothing to save yet: drag a box around the object";
  try {
    saveColorClassInto(session.result()->color_class, yaml_path, cmvision_path);
  } catch (const std::exception& e) {
    return std::string("not saved: ") + e.what();
  }
  return "saved into " + yaml_path + (yaml_path.empty() || cmvision_path.empty() ? "" : " and ") + cmvision_path;
}

CalibrationWindow::CalibrationWindow(CalibrationSession* session, bool live, const std::string& title)
    : session_(session), live_(live), title_(title), shown_(live ? Shown::kLive : Shown::kSessionFrame) {
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
  if (shown_ == Shown::kHeld) return held_frame_;
  if (shown_ == Shown::kSessionFrame && current_ >= 0) return session_->frame(current_).bgr;
  return live_frame_.empty() ? kWaiting : live_frame_;
}

void CalibrationWindow::onMouse(int event, int x, int y, int flags, void* self) {
  static_cast<CalibrationWindow*>(self)->mouse(event, x, y, flags);
}

void CalibrationWindow::mouse(int event, int x, int y, int flags) {
  const cv::Mat& frame = shownFrame();
  // The text band below the frame is not part of it: positions there are the last row.
  const cv::Point at(std::clamp(x, 0, frame.cols - 1), std::clamp(y, 0, frame.rows - 1));
  if (event == cv::EVENT_LBUTTONDOWN) {
    if (shown_ == Shown::kLive) {
      if (live_frame_.empty()) return;  // nothing to box on yet
      held_frame_ = live_frame_.clone();  // the box belongs to the frame it was started on
      shown_ = Shown::kHeld;
    } else if (current_ < 0) {
      return;
    }
    dragging_ = true;
    drag_start_ = at;
    drag_box_ = cv::Rect();
  } else if (event == cv::EVENT_MOUSEMOVE && dragging_ && (flags & cv::EVENT_FLAG_LBUTTON)) {
    drag_box_ = boxBetween(drag_start_, at);
  } else if (event == cv::EVENT_LBUTTONUP && dragging_) {
    dragging_ = false;
    drag_box_ = cv::Rect();
    endDrag(boxBetween(drag_start_, at));
  }
}

void CalibrationWindow::endDrag(const cv::Rect& box) {
  if (shown_ != Shown::kHeld) {
    session_->addBox(current_, box);
    return;
  }
  // A camera frame is kept only with a box on it; a click goes back to the camera.
  const int index = session_->addFrameWithBox(held_frame_, "live frame " + std::to_string(session_->frameCount() + 1), box);
  held_frame_.release();
  if (index >= 0) {
    current_ = index;
    shown_ = Shown::kSessionFrame;
  } else {
    shown_ = Shown::kLive;
  }
}

void CalibrationWindow::keepLiveFrame() {
  current_ = session_->addFrame(live_frame_.clone(), "live frame " + std::to_string(session_->frameCount() + 1));
  shown_ = Shown::kSessionFrame;
}

void CalibrationWindow::stepFrames(int direction) {
  const int count = session_->frameCount();
  if (count == 0 || dragging_) return;
  if (shown_ == Shown::kSessionFrame && current_ >= 0) {
    current_ = (current_ + direction + count) % count;
  } else {
    current_ = direction > 0 ? 0 : count - 1;  // from the camera: the first or the last kept
  }
  held_frame_.release();
  shown_ = Shown::kSessionFrame;
}

CalibrationCommand CalibrationWindow::key(int code) {
  switch (code) {
    case 'q': case 27: return CalibrationCommand::kQuit;
    case 's': return CalibrationCommand::kSave;
    case 't': return live_ ? CalibrationCommand::kSendToTracker : CalibrationCommand::kNone;
    case 'u': if (!dragging_) session_->undo(); break;
    case 'c': session_->cycleSpace(); break;
    case 'n': stepFrames(1); break;
    case 'b': stepFrames(-1); break;
    case ' ':
      if (!live_ || dragging_) break;
      if (shown_ == Shown::kLive) {
        if (!live_frame_.empty()) keepLiveFrame();
      } else {
        shown_ = Shown::kLive;
      }
      break;
    default: break;
  }
  return CalibrationCommand::kNone;
}

void CalibrationWindow::draw() {
  CalibrationView view;
  view.bgr = shownFrame();
  if (shown_ == Shown::kSessionFrame && current_ >= 0) view.boxes = session_->frame(current_).boxes;
  const bool new_mask = view.bgr.data != mask_frame_.data || session_->revision() != mask_revision_;
  if (new_mask) {
    mask_ = session_->classMask(view.bgr);
    mask_frame_ = view.bgr;
    mask_revision_ = session_->revision();
  }
  if (new_mask || view.boxes != counted_boxes_) {  // redraws while dragging count nothing again
    mask_counts_ = CalibrationSession::countMask(mask_, view.boxes);
    counted_boxes_ = view.boxes;
  }
  view.mask = mask_;
  view.dragging = drag_box_;
  view.status = calibrationStatus(*session_, mask_counts_);
  std::string where = "live";
  if (shown_ == Shown::kHeld) where = "live frame (held while the box is dragged)";
  if (shown_ == Shown::kSessionFrame && current_ >= 0) {
    const std::string& name = session_->frame(current_).name;
    where = "frame " + std::to_string(current_ + 1) + "/" + std::to_string(session_->frameCount()) + " " +
            name.substr(name.find_last_of('/') + 1);  // the file, not its folders
  }
  view.status.push_back(notice_.empty() ? where : where + " | " + notice_);
  view.help = live_ ? kLiveHelp : kFilesHelp;
  cv::imshow(title_, renderCalibrationView(view));
}

// The window's close button quits as q does. Some highgui back-ends (GTK) never report the
// window visible: only a window once seen visible and now not counts as closed.
bool CalibrationWindow::closedByUser() {
  const double visible = cv::getWindowProperty(title_, cv::WND_PROP_VISIBLE);
  if (visible >= 1) seen_visible_ = true;
  return seen_visible_ && visible < 1;
}

CalibrationCommand CalibrationWindow::step(int wait_ms) {
  draw();
  const int code = cv::waitKey(wait_ms);
  if (closedByUser()) return CalibrationCommand::kQuit;
  return code < 0 ? CalibrationCommand::kNone : key(code & 0xff);
}

}  // namespace rle_vision
