package io.dtron.engine.internal.verify;

import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.HashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.function.BiConsumer;
import java.util.function.Function;

/**
 * A depth-first search for a lasso in a finite graph of symbolic states given by a successor function (a part of
 * the zone graph: the moves inside a property, the internal moves, the moves without delay), from any number of
 * start states: a path into a cycle, or, with an end condition, a path to a state where it holds (a maximal path
 * that stops). The states from which there is none are remembered across starts. States are compared exactly.
 */
final class CycleSearch {
    private final BiConsumer<SymState, ZoneGraph.Sink> successors;
    private final Function<SymState, String> end;
    private final Budget budget;
    private final Set<Checker.Exact> none = new HashSet<>();

    /**
     * A search for cycles over the successors {@code successors} gives, counting each state it opens in {@code
     * budget}.
     */
    CycleSearch(BiConsumer<SymState, ZoneGraph.Sink> successors, Budget budget) {
        this(successors, s -> null, budget);
    }

    /**
     * A search for cycles, and for paths to a state where {@code end} gives how the path ends there (null where it
     * does not end): a state is asked before its successors are.
     */
    CycleSearch(BiConsumer<SymState, ZoneGraph.Sink> successors, Function<SymState, String> end, Budget budget) {
        this.successors = successors;
        this.end = end;
        this.budget = budget;
    }

    /** How many states are known to start no lasso: the states the searches finished. */
    int finished() {
        return none.size();
    }

    /** A search frame: a state on the stack, its successors, the next one to look at. */
    private static final class Frame {
        final SymState state;
        final Semantics.Move move;
        final List<Semantics.Move> moves = new ArrayList<>();
        final List<SymState> next = new ArrayList<>();
        int index;

        Frame(SymState state, Semantics.Move move) {
            this.state = state;
            this.move = move;
        }
    }

    /**
     * A path from {@code start} into a cycle (its loop start set, its end "a cycle back to state ") or to an end
     * (loop start -1), or null when there is none.
     */
    Checker.Lasso from(SymState start) {
        if (none.contains(new Checker.Exact(start))) {
            return null;
        }
        List<Frame> stack = new ArrayList<>();
        Map<Checker.Exact, Integer> onStack = new HashMap<>();
        Checker.Lasso ended = push(start, null, stack, onStack);
        if (ended != null) {
            return ended;
        }
        while (!stack.isEmpty()) {
            Frame top = stack.get(stack.size() - 1);
            if (top.index == top.next.size()) {
                stack.remove(stack.size() - 1);
                Checker.Exact key = new Checker.Exact(top.state);
                onStack.remove(key);
                none.add(key);
                continue;
            }
            int i = top.index++;
            SymState child = top.next.get(i);
            Checker.Exact key = new Checker.Exact(child);
            if (none.contains(key)) {
                continue;
            }
            Integer loop = onStack.get(key);
            if (loop != null) {
                Checker.Lasso cycle = lasso(stack, loop, "a cycle back to state ");
                cycle.states().add(child);
                cycle.moves().add(top.moves.get(i));
                return cycle;
            }
            ended = push(child, top.moves.get(i), stack, onStack);
            if (ended != null) {
                return ended;
            }
        }
        return null;
    }

    /** Pushes a frame for {@code s} with its successors; returns the path if it ends in {@code s}. */
    private Checker.Lasso push(SymState s, Semantics.Move move, List<Frame> stack,
            Map<Checker.Exact, Integer> onStack) {
        budget.explore();
        Frame f = new Frame(s, move);
        stack.add(f);
        onStack.put(new Checker.Exact(s), stack.size() - 1);
        String ending = end.apply(s);
        if (ending != null) {
            return lasso(stack, -1, ending);
        }
        successors.accept(s, (m, next) -> {
            f.moves.add(m);
            f.next.add(next);
        });
        return null;
    }

    /** The path of the stack's states and the moves between them, as a lasso to complete. */
    private static Checker.Lasso lasso(List<Frame> stack, int loopStart, String ending) {
        List<SymState> states = new ArrayList<>();
        List<Semantics.Move> moves = new ArrayList<>();
        for (int k = 0; k < stack.size(); k++) {
            states.add(stack.get(k).state);
            if (k > 0) {
                moves.add(stack.get(k).move);
            }
        }
        return new Checker.Lasso(states, moves, loopStart, ending);
    }
}
