package io.dtron.model;

import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;

/**
 * Model texts kept in memory under names, so that tools can generate or edit a model and load it again
 * without a file. Thread-safe.
 */
public final class ModelStore {
    private final Map<String, String> texts = new ConcurrentHashMap<>();

    /** Stores (or replaces) the text of model {@code name}; names ending in .xml are XML, others XTA. */
    public void put(String name, String text) {
        texts.put(name, text);
    }

    /** The text stored under {@code name}. */
    public Optional<String> get(String name) {
        return Optional.ofNullable(texts.get(name));
    }

    /** Removes model {@code name}; true if it was there. */
    public boolean remove(String name) {
        return texts.remove(name) != null;
    }

    /** The stored names. */
    public Set<String> names() {
        return Set.copyOf(texts.keySet());
    }
}
