// SpecSlots: rtl/spec_slots.sv's timing - the specular units between the engines and the pix
// register. A pipelined unit (interval 1) is never busy: its latency is the metadata line's
// depth (SlotMeta). An iterative unit (interval > 1) is busy for interval - 1 cycles after it
// starts a beat (en_i = the engines' emit), and the engines wait for it. The values computed are
// the datapath's (model/specular_unit.h); only the busy flag matters to the control.
#pragma once

namespace shadesim {

class SpecSlots {
 public:
  explicit SpecSlots(int interval) : interval_(interval) {}

  bool iterative() const { return interval_ > 1; }
  // busy_o: some slot cannot start a beat this cycle.
  bool busy() const { return busy_ > 0; }

  // The edge, with en_i = the engines' emit. Only an iterative unit counts.
  void clock(bool en) {
    if (!iterative()) return;
    if (en)
      busy_ = interval_ - 1;
    else if (busy_ > 0)
      --busy_;
  }

 private:
  int interval_ = 1;  // cycles per beat
  int busy_ = 0;      // cycles the started beat still needs
};

}  // namespace shadesim
