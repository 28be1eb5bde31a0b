// BeatMeta: what travels with a pixel beat from the engines through the specular slot to the pix
// register - shade_unit.sv's meta_t without the diffuse series values (the cycle model has no
// datapath), and its valid bit.
#pragma once

namespace shadesim {

struct BeatMeta {
  bool valid = false;
  int x = 0;  // lane 0's pixel
  int y = 0;
  bool eor = false;       // holds its span's end-of-row pixel
  int count = 0;          // valid lanes 0 .. count-1: meta_t's mask, which is always a prefix
  int mat = 0;            // its span's material bank
  bool span_end = false;  // its span's last beat (the bank's count drops when it leaves the slot)
};

}  // namespace shadesim
