#include "trace_player.h"
