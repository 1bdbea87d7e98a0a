#include "transcriptions/transcription.h"
