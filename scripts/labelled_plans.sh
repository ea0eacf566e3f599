# Sourced by the scripts that score a topology against the labelled plans of datasets/places (graph_quality.sh,
# bench_topology_runs.sh): labelled_plans prints one line per plan, "name plan-image labels room-ground-truth", the
# files under datasets/places/{maps,labelled,groundtruth} (places::standardLabelledMaps' plans). lab_d is left out:
# its labelled image (992 x 800) and its room ground truth (840 x 581) are two frames.
labelled_plans() {
  cat <<'PLANS'
Fr101 Fr101_original.png training_Fr101.png Freiburg101_scan_gt_segmentation.png
Fr52 Fr52_original.png training_Fr52.png Freiburg52_scan_gt_segmentation.png
NLB NLB_original.png training_NLB_furniture.png NLB_gt_segmentation.png
lab_c lab_c_furnitures_original.png training_lab_c_furnitures.png lab_c_scan_gt_segmentation.png
lab_intel lab_intel_original.png training_intel.png lab_intel_gt_segmentation.png
lab_ipa lab_ipa_original.png training_lab_ipa.png lab_ipa_gt_segmentation.png
office_e office_e_original.png training_office_e.png office_e_gt_segmentation.png
office_h office_h_original.png training_office_h.png office_h_gt_segmentation.png
PLANS
}
