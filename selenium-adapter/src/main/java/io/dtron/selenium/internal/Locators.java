package io.dtron.selenium.internal;

import io.dtron.selenium.AdapterException;
import java.util.Map;
import java.util.Objects;
import java.util.function.Function;
import org.openqa.selenium.By;

/**
 * Not API. Turns locators ({@code id:login-button}, {@code css:#list tr}, {@code xpath://h1},
 * {@code name:username}, {@code link:Log out}, {@code partialLink:Log}, {@code class:status},
 * {@code tag:table}) and the keys of the adapters' properties whose values are locators into Selenium's
 * {@link By}.
 */
public final class Locators {
    private static final Map<String, Function<String, By>> STRATEGIES = Map.of(
            "id", By::id,
            "name", By::name,
            "css", By::cssSelector,
            "xpath", By::xpath,
            "link", By::linkText,
            "partialLink", By::partialLinkText,
            "class", By::className,
            "tag", By::tagName);
    /** The prefixes of the strategies, for messages: {@code class:, css:, ...}. */
    private static final String PREFIXES = String.join(":, ", STRATEGIES.keySet().stream().sorted().toList()) + ":";

    private final Map<String, String> properties;

    /** Locators over the adapters' properties. */
    public Locators(Map<String, String> properties) {
        this.properties = Map.copyOf(properties);
    }

    /**
     * A resolved locator.
     *
     * @param description the key and the locator ({@code LOGIN_BUTTON (id:login-button)}) or the locator alone
     * @param by          Selenium's locator
     */
    public record Locator(String description, By by) {
        @Override
        public String toString() {
            return description;
        }
    }

    /**
     * Resolves a key of the properties or a locator.
     *
     * @throws AdapterException if it is neither, or the key's value is no locator
     */
    public Locator resolve(String keyOrLocator) {
        Objects.requireNonNull(keyOrLocator, "keyOrLocator");
        By direct = parse(keyOrLocator);
        if (direct != null) {
            return new Locator(keyOrLocator, direct);
        }
        String value = properties.get(keyOrLocator);
        if (value == null) {
            throw new AdapterException("'" + keyOrLocator + "' is neither a key of the adapters' properties nor a"
                    + " locator (" + PREFIXES + ")");
        }
        By by = parse(value);
        if (by == null) {
            throw new AdapterException("the value of " + keyOrLocator + ", '" + value + "', is no locator: start it"
                    + " with one of " + PREFIXES);
        }
        return new Locator(keyOrLocator + " (" + value + ")", by);
    }

    private static By parse(String text) {
        int colon = text.indexOf(':');
        if (colon <= 0 || colon == text.length() - 1) {
            return null;
        }
        Function<String, By> strategy = STRATEGIES.get(text.substring(0, colon));
        return strategy == null ? null : strategy.apply(text.substring(colon + 1));
    }

    /** Returns an XPath string literal of {@code text}, whatever quotes it contains. */
    public static String xpathLiteral(String text) {
        if (text.indexOf('\'') < 0) {
            return "'" + text + "'";
        }
        if (text.indexOf('"') < 0) {
            return "\"" + text + "\"";
        }
        return "concat('" + text.replace("'", "', \"'\", '") + "')";
    }
}
