#include "lsdem/contact/SceneFile.h"
