// Frame sequences (brume render --sequence A-B): which frames a render range writes and how the
// temporal history reaches each one, so that any frame's image depends on its number alone.
//
// The history is an exponential blend with infinite memory, so a range cannot start where a longer
// render would have been. Instead the history restarts at fixed frames: frame f belongs to block
// floor(f / K), and the history of that block starts W frames before it (warm-up frames rendered and
// not written), at chainStart(f) = floor(f / K) * K - W. Every frame is then rendered from the same
// history chain whether the range starts at 0, at f or in between: a range split in two gives the same
// images bit for bit. W is the number of frames after which the starting history weighs at most 1%
// (history_weight^W <= 0.01), so a restart changes an image by less than 1% of the frame-to-frame
// temporal noise; K = 4 W keeps the warm-up at 25% of the frames of a long range.
#pragma once

#include <optional>
#include <string_view>

#include "scene.h"

namespace brume {

struct FrameRange {
    int first = 0;
    int last = 0;  // inclusive
};

inline constexpr int kMaxSequenceFrame = 9999999;

// "A-B" with integers 0 <= A <= B <= kMaxSequenceFrame; nothing else.
std::optional<FrameRange> parseFrameRange(std::string_view text);

// W: frames rendered before a block's first frame (0 when temporal accumulation is off).
int temporalWarmupFrames(const Temporal& t);
// K: frames of a block (at least 1).
int temporalBlockFrames(const Temporal& t);
// The frame where the history that frame f sees begins (f itself when there is no history).
int historyChainStart(int frame, const Temporal& t);

}  // namespace brume
