"""Trains a small flow network on a FlowScape release for a few hundred steps, printing the
falling loss, evaluating EPE per weather on the test split and saving checkpoints (resume with
--resume). Runs on the CPU, or on CUDA when torch sees a GPU.

    build/apps/gen_flowscape --maps 1 --frames 10 --resolution 64 --face-size 32 --spp 4 --out small
    build/apps/flowscape_split small
    PYTHONPATH=python:build/python python3 python/examples/train_small.py small --steps 300
"""
import argparse
import os
import sys
import time

import torch
from torch import nn

import flowscape


class TinyFlow(nn.Module):
    """Both frames and the pixel's latitude and longitude in, flow out: a few dilated
    convolutions, enough to learn how the ego motion moves each part of the panorama."""

    def __init__(self, width=32):
        super().__init__()
        layers, channels = [], 8
        for dilation in (1, 2, 4, 8, 1):
            layers += [nn.Conv2d(channels, width, 3, padding=dilation, dilation=dilation), nn.ReLU()]
            channels = width
        self.body = nn.Sequential(*layers)
        self.head = nn.Conv2d(width, 2, 3, padding=1)

    def forward(self, img1, img2):
        b, _, h, w = img1.shape
        ys = torch.linspace(-1, 1, h, device=img1.device)[:, None].expand(h, w)
        xs = torch.linspace(-1, 1, w, device=img1.device)[None, :].expand(h, w)
        where = torch.stack([xs, ys])[None].expand(b, 2, h, w)
        return self.head(self.body(torch.cat([img1 / 255.0 - 0.5, img2 / 255.0 - 0.5, where], 1)))


def evaluate_and_save(model, optimizer, step, test, device, folder):
    """EPE per weather on the test split (the paper's Table III rows), then a checkpoint."""
    model.eval()
    rows = flowscape.evaluate_by_weather(model, test, device=device)
    model.train()
    print(f"step {step:4d}  test EPE " + "  ".join(
        f"{weather} {row['epe']:.3f}" for weather, row in sorted(rows.items())))
    os.makedirs(folder, exist_ok=True)
    state = {"model": model.state_dict(), "optimizer": optimizer.state_dict(), "step": step,
             "test_epe": {weather: row["epe"] for weather, row in rows.items()}}
    for name in (f"checkpoint-{step:06d}.pt", "latest.pt"):
        partial = os.path.join(folder, "." + name + ".partial")
        torch.save(state, partial)
        os.replace(partial, os.path.join(folder, name))  # never a half-written checkpoint


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("release")
    parser.add_argument("--steps", type=int, default=300)
    parser.add_argument("--batch", type=int, default=4)
    parser.add_argument("--crop", type=int, nargs=2, default=None,
                        help="cyclic crop height width (default: the whole panorama)")
    parser.add_argument("--fda", choices=("r", "e", "none"), default="none")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--lr", type=float, default=2e-3)
    parser.add_argument("--eval-every", type=int, default=100,
                        help="steps between evaluations on the test split (0: only at the end)")
    parser.add_argument("--checkpoints", default="checkpoints",
                        help="folder for checkpoint-<step>.pt and latest.pt")
    parser.add_argument("--resume", action="store_true", help="continue from <checkpoints>/latest.pt")
    args = parser.parse_args()
    device = "cuda" if torch.cuda.is_available() else "cpu"
    torch.manual_seed(0)
    augmentation = flowscape.Augmentation(fda=None if args.fda == "none" else args.fda,
                                          crop=args.crop and tuple(args.crop), shift=False,
                                          jitter=True)
    train = flowscape.FlowScape(args.release, "train", transform=augmentation)
    if len(train) < args.batch:  # drop_last would leave no batch at all: the loop would spin
        sys.exit(f"train_small.py: {args.release}: the train split has {len(train)} pairs, fewer "
                 f"than --batch {args.batch}; lower --batch or render more frames")
    loader = torch.utils.data.DataLoader(train, batch_size=args.batch, shuffle=True,
                                         num_workers=args.workers, drop_last=True,
                                         persistent_workers=args.workers > 0)
    test = flowscape.FlowScape(args.release, "test", extras=("meta",))
    model = TinyFlow().to(device)
    optimizer = torch.optim.AdamW(model.parameters(), lr=args.lr)
    step = 0
    if args.resume:
        state = torch.load(os.path.join(args.checkpoints, "latest.pt"), map_location=device)
        model.load_state_dict(state["model"])
        optimizer.load_state_dict(state["optimizer"])
        step = state["step"]
    print(f"{len(train)} training pairs, {len(test)} test pairs, device {device}, native extension "
          f"{'yes' if flowscape.native_available() else 'no (numpy)'}")
    start, window, first, last = time.time(), [], None, None
    while step < args.steps:
        for img1, img2, flow, valid in loader:
            img1, img2, flow, valid = (t.to(device) for t in (img1, img2, flow, valid))
            error = (model(img1, img2) - flow).norm(dim=1)
            loss = (error * valid).sum() / valid.sum().clamp(min=1)
            optimizer.zero_grad()
            loss.backward()
            optimizer.step()
            window.append(loss.item())
            step += 1
            if step % 25 == 0 or step >= args.steps:  # a report every 25 steps and at the end
                last = sum(window) / len(window)
                first = last if first is None else first
                print(f"step {step:4d}  EPE loss {last:7.3f}  ({time.time() - start:5.1f} s)")
                window = []
            if step >= args.steps or (args.eval_every and step % args.eval_every == 0):
                evaluate_and_save(model, optimizer, step, test, device, args.checkpoints)
            if step >= args.steps:
                break
    if first is not None:  # None: resumed at or past --steps, nothing trained
        print(f"loss fell from {first:.3f} to {last:.3f}" if last < first else
              f"loss did not fall ({first:.3f} -> {last:.3f})")


if __name__ == "__main__":
    main()
