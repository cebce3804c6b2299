package io.dtron.models.streetlight.adapters;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.AdapterException;
import io.dtron.selenium.ChannelVariables;
import jakarta.inject.Inject;
import jakarta.inject.Named;

/** {@code i_login(user)}: opens the login page and logs in as operator {@code user<N>}. */
@ChannelVariables("user")
public final class Login extends AbstractSeleniumAdapter {
    private final String baseUrl;
    private final String password;
    private final String userNameLabel;
    private final String passwordLabel;

    /** The adapter with the application's address, the password and the labels of the login form. */
    @Inject
    public Login(@Named("BASE_URL") String baseUrl, @Named("PASSWORD") String password,
                 @Named("USER_NAME_LABEL") String userNameLabel, @Named("PASSWORD_LABEL") String passwordLabel) {
        this.baseUrl = baseUrl;
        this.password = password;
        this.userNameLabel = userNameLabel;
        this.passwordLabel = passwordLabel;
    }

    @Override
    protected void execute(IDtronChannelValued message) {
        getWebDriver().get(baseUrl + "/login");
        findInput(userNameLabel).sendKeys(operator());
        findInput(passwordLabel).sendKeys(password);
        findElement("LOGIN_BUTTON").click();
        requireLoggedIn();
    }

    /**
     * The post-condition of logging in: the page says the current message's operator is logged in.
     *
     * @throws AdapterException if it names another operator or none
     */
    public void requireLoggedIn() {
        String shown = findElement("CURRENT_USER").getText();
        if (!shown.equals(operator())) {
            throw new AdapterException("the page says " + shown + " is logged in, not " + operator());
        }
    }

    private String operator() {
        return "user" + getUser();
    }
}
