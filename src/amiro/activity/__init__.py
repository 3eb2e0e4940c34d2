"""Activity recognition: skeletons, normalisation, the multi-stage LSTM model."""
