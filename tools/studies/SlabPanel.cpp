// SlabPanel: being written (see tools/studies/SlabPanel.h when it lands).
