// The clock loop of a stage fed one beat per ce under the block-test ce schedule (CeGen),
// shared by the benches of the blocks that fold (tb_dp, tb_wta, tb_right_wta). Folded (f > 1),
// beat 0's input is driven on the f clocks after reset and every beat's input is held from
// the clock after the previous ce up to its own (the input-stability rule, docs/algorithm.md
// "Folded datapath"); unfolded, the idle clocks get garbage.
#pragma once

#include <cstddef>

namespace sm::test {

// make(bi): beat bi's input, made once and held; drive(in) puts it on the ports; garbage()
// drives random inputs on an unfolded idle clock; idle(bi) runs after each idle clock before
// beat bi's ce and on_ce(bi) after that ce (false: stop).
template <class Bench, class Make, class Drive, class Garbage, class Idle, class OnCe>
void run_held_beats(Bench& t, size_t n, int f, Make&& make, Drive&& drive, Garbage&& garbage, Idle&& idle,
                    OnCe&& on_ce) {
  auto& tb = t.tb();
  if (n == 0) return;
  auto in = make(size_t{0});
  if (f > 1) {  // the first beat's sub-steps run on the f clocks after reset
    tb->ce = 0;
    drive(in);
    for (int i = 0; i < f; ++i) tb.tick();
  }
  for (size_t bi = 0; bi < n; ++bi) {
    if (bi > 0) in = make(bi);
    while (!t.next_ce()) {
      if (f > 1)
        drive(in);  // folded: the beat is held until its ce
      else
        garbage();
      tb.tick();
      idle(bi);
    }
    drive(in);
    tb.tick();
    if (!on_ce(bi)) return;
  }
}

}  // namespace sm::test
