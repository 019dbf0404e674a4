// The parameters of both hair passes of mboit (std140).
#include "slots.h"
#include "uniforms.h"
