#!/usr/bin/env python3
"""torch_ref: the generator's training step in PyTorch, the yardstick of the
trainer's speed (design.md §10). Not run by `make check` or CI; needs Debian's
python3-torch. Same architecture as the reference configuration of
`crownshy bench-model` (src/model/model.c, pairattn.c): tokens of 24 deviation
values plus 12 features, width 64, 3 pre-LN blocks of 4-head attention and a
GELU (tanh form) MLP of 256, the stand/time embedding added to every token, a
linear head of 24; the pair model adds, per block, a score bias and a value
term from 8 standardised pair features; the independent arm attends to itself
only. One optimiser step: flow-matching loss (linear path, MSE on velocity)
on a batch of 64 patches x 24 tokens, backward, AdamW. One thread.

Times are process CPU seconds (like bench-model's thread CPU time), so a
loaded machine slows the wall clock, not the figure.

usage: python3 tests/bench/torch_ref.py [--steps 20] [--repeats 5] [--threads 1]
prints one line per model: median steps/s [min, max] over the repeats.
"""
import argparse
import statistics
import time

import torch
import torch.nn as nn
import torch.nn.functional as F

T, P, NFEAT, NCOND, NTIME = 24, 24, 12, 5, 16
C, L, H, FF, Q = 64, 3, 4, 256, 8


class Block(nn.Module):
    def __init__(self, pair):
        super().__init__()
        self.ln1, self.ln2 = nn.LayerNorm(C), nn.LayerNorm(C)
        self.qkv, self.proj = nn.Linear(C, 3 * C), nn.Linear(C, C)
        self.fc1, self.fc2 = nn.Linear(C, FF), nn.Linear(FF, C)
        self.pair = pair
        if pair:
            self.wb = nn.Linear(Q, H, bias=False)   # score bias per head
            self.wv = nn.Linear(Q, C, bias=False)   # value term

    def attention(self, x, phi, mask):
        B = x.shape[0]
        q, k, v = self.qkv(x).view(B, T, 3, H, C // H).permute(2, 0, 3, 1, 4)
        s = q @ k.transpose(-1, -2) / (C // H) ** 0.5            # B H T T
        if self.pair:
            s = s + self.wb(phi).permute(0, 3, 1, 2) / (C // H) ** 0.5
        if mask is not None:
            s = s.masked_fill(mask, float("-inf"))
        a = s.softmax(-1)
        o = (a @ v).transpose(1, 2).reshape(B, T, C)
        if self.pair:
            mix = torch.einsum("bhij,bijq->bhiq", a, phi)           # B H T Q
            wv = self.wv.weight.view(H, C // H, Q)
            o = o + torch.einsum("bhiq,hdq->bihd", mix, wv).reshape(B, T, C)
        return self.proj(o)

    def forward(self, x, phi, mask):
        x = x + self.attention(self.ln1(x), phi, mask)
        return x + self.fc2(F.gelu(self.fc1(self.ln2(x)), approximate="tanh"))


class Flow(nn.Module):
    def __init__(self, pair, joint):
        super().__init__()
        self.tok = nn.Linear(P + NFEAT, C)
        self.e1, self.e2 = nn.Linear(NCOND + NTIME, C), nn.Linear(C, C)
        self.blocks = nn.ModuleList(Block(pair) for _ in range(L))
        self.lnf, self.head = nn.LayerNorm(C), nn.Linear(C, P)
        self.mask = None if joint else ~torch.eye(T, dtype=torch.bool)

    def forward(self, xt, feat, cond, t, phi):
        k = torch.arange(NTIME // 2, dtype=torch.float32)
        w = torch.pi * 2.0 ** k * t[:, None]
        e = self.e2(F.gelu(self.e1(torch.cat([cond, w.sin(), w.cos()], 1)), approximate="tanh"))
        x = self.tok(torch.cat([xt, feat], 2)) + e[:, None, :]
        for b in self.blocks:
            x = b(x, phi, self.mask)
        return self.head(self.lnf(x))


def bench(pair, joint, steps, repeats, B=64):
    torch.manual_seed(1)
    m = Flow(pair, joint)
    opt = torch.optim.AdamW(m.parameters(), lr=2e-3)
    x1, feat = torch.randn(B, T, P), torch.randn(B, T, NFEAT)
    cond, phi = torch.randn(B, NCOND), torch.randn(B, T, T, Q)

    def step():
        t = torch.rand(B)
        x0 = torch.randn(B, T, P)
        xt = (1 - t[:, None, None]) * x0 + t[:, None, None] * x1
        loss = F.mse_loss(m(xt, feat, cond, t, phi), x1 - x0)
        opt.zero_grad(set_to_none=True)
        loss.backward()
        opt.step()

    for _ in range(3):
        step()
    rates = []
    for _ in range(repeats):
        t0 = time.process_time()
        for _ in range(steps):
            step()
        rates.append(steps / (time.process_time() - t0))
    return rates


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--threads", type=int, default=1)
    a = ap.parse_args()
    torch.set_num_threads(a.threads)
    print(f"torch {torch.__version__}, {a.threads} thread(s), batch 64 x {T} tokens, "
          f"median [min, max] of {a.repeats} x {a.steps} steps, process CPU time")
    for name, pair, joint in (("plain", False, True), ("pair", True, True), ("pair_indep", True, False)):
        r = bench(pair, joint, a.steps, a.repeats)
        print(f"torch_{name}_steps_per_s\t{statistics.median(r):.2f}\t[{min(r):.2f}, {max(r):.2f}]")


if __name__ == "__main__":
    main()
