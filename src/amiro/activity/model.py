"""The paper's multi-stage classifier (section 3.5, Figure 6), in PyTorch (training only).

Three stages, each linear feature layers then an LSTM over the frames; stages 2 and 3 see
the skeleton features and the previous stage's per-frame class probabilities, so each
stage refines the last.  Every stage is trained with its own loss; stage 3 predicts.
"""

from __future__ import annotations

import torch
from torch import nn


class Stage(nn.Module):
    def __init__(self, inputs: int, hidden: int, classes: int) -> None:
        super().__init__()
        self.features = nn.Sequential(
            nn.Linear(inputs, hidden), nn.ReLU(), nn.Linear(hidden, hidden), nn.ReLU()
        )
        self.lstm = nn.LSTM(hidden, hidden, batch_first=True)
        self.head = nn.Linear(hidden, classes)

    def forward(
        self, x: torch.Tensor, h: torch.Tensor, c: torch.Tensor
    ) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        seq, (h, c) = self.lstm(self.features(x), (h, c))
        return self.head(seq), h, c


class MultiStageLSTM(nn.Module):
    """``forward(x, h0, c0)``: x ``(B, T, F)``, states ``(stages, B, hidden)``; returns the
    per-stage logits ``(stages, B, T, classes)`` and the final states."""

    def __init__(self, features: int, classes: int, hidden: int = 64, stages: int = 3) -> None:
        super().__init__()
        self.hidden = hidden
        self.stages = nn.ModuleList(
            Stage(features if i == 0 else features + classes, hidden, classes)
            for i in range(stages)
        )

    def initial_state(self, batch: int) -> tuple[torch.Tensor, torch.Tensor]:
        zeros = torch.zeros(len(self.stages), batch, self.hidden)
        return zeros, zeros.clone()

    def forward(
        self, x: torch.Tensor, h0: torch.Tensor, c0: torch.Tensor
    ) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        logits, hs, cs = [], [], []
        inputs = x
        for i, stage in enumerate(self.stages):
            out, h, c = stage(inputs, h0[i : i + 1], c0[i : i + 1])
            logits.append(out)
            hs.append(h)
            cs.append(c)
            inputs = torch.cat([x, out.softmax(dim=-1)], dim=-1)
        return torch.stack(logits), torch.cat(hs), torch.cat(cs)


class LastFrameProbabilities(nn.Module):
    """What the runtime needs: stage 3's class probabilities at the last frame, and the
    states, so one ONNX graph serves whole windows and frame-by-frame streaming."""

    def __init__(self, model: MultiStageLSTM) -> None:
        super().__init__()
        self.model = model

    def forward(
        self, x: torch.Tensor, h0: torch.Tensor, c0: torch.Tensor
    ) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        logits, h, c = self.model(x, h0, c0)
        return logits[-1, :, -1].softmax(dim=-1), h, c
