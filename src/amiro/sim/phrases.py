"""What simulated residents say, in English, Romanian and French.

Small tables, several variants each, so that the dialogue stack sees varied wording (and the
rule-based NLU gets exercised) while the oracle intent stays known.
"""

from __future__ import annotations

# PHRASES[lang][context][reply] -> variants; context "hydration" for hydration reminders,
# "generic" for everything else.
PHRASES: dict[str, dict[str, dict[str, tuple[str, ...]]]] = {
    "en": {
        "hydration": {
            "confirm": (
                "yes, I will drink a glass of water now",
                "okay, I'll have some water",
                "sure, thank you, I'm drinking now",
            ),
            "deny": (
                "no, I'm not thirsty",
                "no thanks, I don't want water",
                "no, leave me alone",
            ),
            "postpone": (
                "later, please",
                "remind me in a few minutes",
                "not now, maybe later",
            ),
        },
        "generic": {
            "confirm": ("yes", "yes, that's right", "sure"),
            "deny": ("no", "no, that's wrong", "not at all"),
            "postpone": ("later", "ask me later", "not now"),
        },
    },
    "ro": {
        "hydration": {
            "confirm": (
                "da, beau un pahar cu apă acum",
                "bine, beau niște apă",
                "sigur, mulțumesc, beau acum",
            ),
            "deny": (
                "nu, nu mi-e sete",
                "nu, mulțumesc, nu vreau apă",
                "nu, lasă-mă în pace",
            ),
            "postpone": (
                "mai târziu, te rog",
                "amintește-mi peste câteva minute",
                "nu acum, poate mai târziu",
            ),
        },
        "generic": {
            "confirm": ("da", "da, așa este", "sigur"),
            "deny": ("nu", "nu, nu este corect", "deloc"),
            "postpone": ("mai târziu", "întreabă-mă mai târziu", "nu acum"),
        },
    },
    "fr": {
        "hydration": {
            "confirm": (
                "oui, je vais boire un verre d'eau",
                "d'accord, je bois un peu d'eau",
                "bien sûr, merci, je bois maintenant",
            ),
            "deny": (
                "non, je n'ai pas soif",
                "non merci, je ne veux pas d'eau",
                "non, laisse-moi tranquille",
            ),
            "postpone": (
                "plus tard, s'il te plaît",
                "rappelle-moi dans quelques minutes",
                "pas maintenant, peut-être plus tard",
            ),
        },
        "generic": {
            "confirm": ("oui", "oui, c'est ça", "bien sûr"),
            "deny": ("non", "non, ce n'est pas ça", "pas du tout"),
            "postpone": ("plus tard", "demande-moi plus tard", "pas maintenant"),
        },
    },
}

# ground-truth intent labels for the oracle NLU
INTENTS = {"confirm": "affirm", "deny": "deny", "postpone": "postpone"}


def context_of(prompt_kind: str) -> str:
    return "hydration" if prompt_kind == "hydration_reminder" else "generic"
