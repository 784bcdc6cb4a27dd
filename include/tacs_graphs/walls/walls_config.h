// Section `walls` of the pipeline configuration: extraction (wall_extraction node), association
// and dominant axes (backend, room segmentation).
#pragma once

#include "tacs_graphs/walls/dominant_axes.h"
#include "tacs_graphs/walls/wall_extractor.h"
#include "tacs_graphs/walls/wall_map.h"

namespace tacs {

struct WallsConfig {
  WallExtractionConfig extraction;
  WallAssociationConfig association;
  DominantAxesConfig axes;

  template <class V>
  void visit(V& v) {
    v("extraction", extraction);
    v("association", association);
    v("axes", axes);
  }
  void validate() const {
    extraction.validate();
    association.validate();
    axes.validate();
  }
};

}  // namespace tacs
