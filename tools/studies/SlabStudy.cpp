// SlabStudy: being written (see tools/studies/SlabStudy.h when it lands).
