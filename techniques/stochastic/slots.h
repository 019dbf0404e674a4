// stochastic: the params and the sample depths in the hair passes (beside the
// shadow lookup), the resolve's inputs (a full-screen pass)
// Its own binding names, for its C++ (#include "techniques/stochastic/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_STOCHASTIC_SLOTS_H
#define SB_STOCHASTIC_SLOTS_H

#define SB_SLOT_STOCH_PARAMS 16
#define SB_SLOT_STOCH_DEPTHS 18
#define SB_SLOT_STOCH_ACCUM 16
#define SB_SLOT_STOCH_ALPHA 17

#endif  // SB_STOCHASTIC_SLOTS_H
