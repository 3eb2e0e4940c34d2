"""The activities amiro recognises: the paper's eight NTU RGB+D actions, plus falling.

One list for the model, the synthetic motion and the simulated residents, so a label can
never mean one thing to the simulator and another to the classifier.
"""

from __future__ import annotations

ACTIONS: tuple[str, ...] = (
    "drink_water",
    "standing_up",
    "hand_waving",
    "play_phone",
    "typing",
    "pointing",
    "sneeze_cough",
    "touch_chest",
    "falling",
)
NTU_ACTION_IDS: dict[str, int] = {
    "drink_water": 1,
    "standing_up": 9,
    "hand_waving": 23,
    "play_phone": 29,
    "typing": 30,
    "pointing": 31,
    "sneeze_cough": 41,
    "touch_chest": 45,
    "falling": 43,
}
# The model's extra outcome for every other action (trained on real examples of them):
# the recogniser reports no activity for it.
UNKNOWN = "unknown"
IDLE = "idle"  # the simulated residents' resting state: not a class of the model
